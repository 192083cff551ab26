// SPDX-License-Identifier: Apache-2.0
// The gnuplot script behind report.png: what the run's CSV files hold, and the panels drawn.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "mrh/report/report.h"

namespace mrh::report::internal {

/// What report.png needs to know about ticks.csv before plotting it.
struct TickScan {
  double t_first = 0.0, t_last = 0.0;  ///< s; both 0 without data rows
  std::int64_t rows = 0;
  bool has_safety = false;          ///< the `safety` column exists (column 16)
  std::int64_t clamped = 0;         ///< ticks with the force or torque clamped
  std::int64_t contact_losses = 0;  ///< ticks whose contact count fell to 0
};

/// One moving body of bodies.csv.
struct BodyTrace {
  std::string name;
  int index = 0;           ///< its row within every physics step (rows come in body order)
  Vec3 p0 = Vec3::Zero();  ///< body origin in the first row (m, world)
  double max_moved = 0.0;  ///< largest distance of the origin from p0 (m)
};

/// What report.png needs to know about bodies.csv.
struct BodyScan {
  std::vector<BodyTrace> bodies;  ///< in file order
  double t_last = 0.0;            ///< s
};

/// Reads the ticks.csv at `path` (missing or empty: zero rows). Not RT-safe.
TickScan ScanTicks(const std::filesystem::path& path);

/// Reads the bodies.csv at `path` (missing or empty: no bodies). Not RT-safe.
BodyScan ScanBodies(const std::filesystem::path& path);

/// The bodies the objects panel draws: all of them up to options.max_legend_bodies, otherwise
/// the touched ones (options.touched_bodies) and then the most moved, that many in all.
std::vector<BodyTrace> BodiesToDraw(const BodyScan& scan, const ReportOptions& options);

/// The whole report.gp text: panels, legends, marks and one time axis for all panels.
std::string ReportScript(const std::string& title, const ReportOptions& options,
                         const TickScan& ticks, const BodyScan& bodies);

}  // namespace mrh::report::internal
