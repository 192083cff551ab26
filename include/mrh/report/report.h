// SPDX-License-Identifier: Apache-2.0
// Run output: ticks.csv, bodies.csv, steps.csv, summary.json and report.png in one folder.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "mrh/engine/engine.h"

namespace mrh::report {

/// Writes ticks.csv, bodies.csv and steps.csv into `dir` as records arrive (buffered). Not
/// RT-safe: the engine calls it from its non-RT side.
///
/// bodies.csv has one row per moving body per physics step:
/// `t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,cx,cy,cz` — t (s), the body's name, its body
/// frame's origin (m) and orientation (body → world) as in the scene's MJCF, its centre of mass's
/// linear velocity (m/s) and its angular velocity (rad/s), both world frame, and the centre of
/// mass's position (m, world frame).
class CsvRecorder : public physics::Recorder {
 public:
  /// Creates `dir` if needed. With two or more `pointer_names` (the pointers' body names, in
  /// pointer order) ticks.csv gains a last column `pointer` naming each row's pointer (one row
  /// per pointer per tick); with one or none it is unchanged.
  /// @throws mrh::RuntimeError if a file cannot be opened.
  explicit CsvRecorder(const std::filesystem::path& dir,
                       std::vector<std::string> pointer_names = {});
  ~CsvRecorder() override;
  void OnTick(const ir::TickRecord& tick) override;
  void OnStep(const physics::StepRecord& step, const world::World& world) override;
  /// Flushes and closes the files. @throws mrh::RuntimeError on a write error.
  void Close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The text of summary.json (method, mode, rates, ticks, overruns, jitter, max force, per-body
/// impulses, faults, warnings), pretty-printed, ending in a newline. `session_file` and
/// `scene_file` name the run's inputs. Not RT-safe.
std::string SummaryJson(const engine::RunStats& stats, const std::string& session_file,
                        const std::string& scene_file);

/// Writes SummaryJson into dir/summary.json, creating `dir` if needed.
/// @throws mrh::RuntimeError if the file cannot be written.
void WriteSummary(const std::filesystem::path& dir, const engine::RunStats& stats,
                  const std::string& session_file, const std::string& scene_file);

/// What report.png draws beyond the force and pointer panels.
struct ReportOptions {
  /// A 6-DOF method: adds the torque panel and the pointer orientation panel. A 3-DOF method
  /// (false) renders no torque, so neither panel is drawn.
  bool six_dof = true;
  /// Names of the bodies the pointer touched (e.g. RunStats::impulses with a non-zero impulse):
  /// when the scene has more moving bodies than max_legend_bodies, these are drawn first.
  std::vector<std::string> touched_bodies = {};
  /// At most this many bodies get a line and a legend entry in the objects panel; beyond it the
  /// panel's title says how many are left out. >= 1.
  int max_legend_bodies = 8;
  /// The pointers' body names of a run with several pointers (RunStats::pointers), in pointer
  /// order: with two or more, the force panel draws each pointer's |f| and the position panel
  /// each pointer's x, y, z, one colour per pointer (ticks.csv has one row per pointer per tick,
  /// in this order). Empty: one pointer.
  std::vector<std::string> pointers = {};
};

/// Writes dir/report.gp and runs gnuplot on it to draw dir/report.png from dir/ticks.csv and
/// dir/bodies.csv. Panels, top to bottom, all on one time axis (the run's first to last record):
///  - force: f_x, f_y, f_z and |f|, with a mark on every tick whose force or torque the safety
///    layer clamped (ticks.csv `safety`) and on every tick where the contact count fell to 0;
///  - torque (6-DOF methods only);
///  - pointer position;
///  - pointer orientation as a rotation vector in degrees (6-DOF methods only);
///  - objects (when bodies.csv has rows): each body's distance from its start, |p - p0| of its
///    body origin, one line and legend entry per body (see ReportOptions::max_legend_bodies).
/// Returns false (and a one-line reason in *why) if gnuplot is missing or fails; the run still
/// counts. Not RT-safe.
bool PlotReport(const std::filesystem::path& dir, const std::string& title, std::string* why,
                const ReportOptions& options);

/// PlotReport with ReportOptions{.six_dof = renders_torque}.
bool PlotReport(const std::filesystem::path& dir, const std::string& title, std::string* why,
                bool renders_torque = true);

/// report.png for a run of `session_file`, as `mrh run` draws it: PlotReport titled
/// "<session file name>: <method> (<mode>)", without the torque and orientation panels for the
/// 3-DOF methods (single-rate, impulse, local-dynamics), which render a force only, and with the
/// bodies the pointer pushed (non-zero RunStats::impulses) in the objects legend.
bool PlotRunReport(const std::filesystem::path& dir, const std::filesystem::path& session_file,
                   const engine::RunStats& stats, std::string* why);

/// Runs gnuplot on dir/script (working directory `dir`) and checks that it wrote dir/png.
/// Returns false with a one-line reason in *why if gnuplot is missing or fails.
bool RunGnuplotScript(const std::filesystem::path& dir, const std::string& script,
                      const std::string& png, std::string* why);

}  // namespace mrh::report
