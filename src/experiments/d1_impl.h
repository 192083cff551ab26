// SPDX-License-Identifier: Apache-2.0
// Demo D1's runs (d1_run.cc) as its report (d1.cc) reads them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "mrh/engine/engine.h"

namespace mrh::session {
struct Session;
}

namespace mrh::experiments::internal {

/// One physics step of a D1 run: a row of d1.csv.
struct D1Step {
  double t = 0.0;               ///< s, simulated time at the end of the step
  double step_ms = 0.0;         ///< physics step wall time
  int sim_contacts = 0;         ///< MuJoCo contacts
  int neighbors = 0;            ///< bodies near the pointer
  double max_body_speed = 0.0;  ///< m/s, fastest object's centre of mass
  double hand_speed = 0.0;      ///< m/s, fastest pointer motion over the period's ticks
  int contact_ticks = 0;        ///< ticks of the period with a pointer contact
};

/// What a D1 run did, beyond RunStats.
struct D1Run {
  engine::RunStats stats;
  std::vector<D1Step> steps;
  int objects = 0;  ///< free bodies of the scene
  /// The table's top: centre, half extents (m, world; x, y) and the height of its surface.
  double table_x = 0.0, table_y = 0.0, table_hx = 0.0, table_hy = 0.0, table_top = 0.0;
  double max_body_speed = 0.0;          ///< m/s, over every object and step
  std::string fastest_body;             ///< the object that reached it
  double fastest_t = 0.0;               ///< s, when
  double max_hand_speed = 0.0;          ///< m/s, the pointer's, between consecutive ticks
  double max_contact_hand_speed = 0.0;  ///< m/s, the same over ticks with a pointer contact
  double max_drop = 0.0;           ///< m, the largest fall of any object's centre below its start
  double max_displacement = 0.0;   ///< m, the largest distance of any object from its start
  int off_table = 0;               ///< objects whose centre of mass left the table top at some step
  std::string first_off_table;     ///< the first of them ("" if none)
  std::int64_t contact_ticks = 0;  ///< ticks with at least one pointer contact
  int touched_objects = 0;         ///< objects that received a reaction impulse from the pointer
  double last_tick_t = 0.0;        ///< s, time of the last haptic tick recorded
  std::int64_t recorded_ticks = 0;  ///< ticks the recorder received
};

/// Runs `session` (D1's scene) and records every step. The scene must have a static box geom
/// named "table". @throws mrh::SceneError if it has none.
D1Run RunD1Session(const session::Session& session);

/// Peak resident set size of this process so far (MB, 10^6 bytes).
double PeakRssMb();

}  // namespace mrh::experiments::internal
