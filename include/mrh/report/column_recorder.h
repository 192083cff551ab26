// SPDX-License-Identifier: Apache-2.0
// ColumnRecorder: a run's ticks, bodies and steps held in memory as the columns of its CSV files.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "mrh/engine/engine.h"

namespace mrh::report {

/// The columns of ticks.csv, in file order: time (s), pointer position (m) and orientation
/// (quaternion w, x, y, z) and the displayed force (N) and torque (N·m), all in the world
/// frame, the contact count and the tick's device::SafetyBits (4 = force clamped, 8 = torque
/// clamped). `safety` is last so that readers indexing the first fifteen columns keep working.
inline constexpr std::array<std::string_view, 16> kTickColumns = {
    "t",  "px", "py", "pz", "qw", "qx", "qy",       "qz",
    "fx", "fy", "fz", "tx", "ty", "tz", "contacts", "safety"};

/// The columns of bodies.csv, in file order: time at the end of the step (s), body name, body
/// frame origin (m) and orientation (w, x, y, z) as MuJoCo defines the body in the scene, linear
/// (m/s) and angular (rad/s) velocity of the centre of mass, and the centre of mass (m); world
/// frame. One row per moving body per physics step. The centre-of-mass columns come last so that
/// readers indexing the first fifteen columns keep working.
inline constexpr std::array<std::string_view, 18> kBodyColumns = {
    "t",  "body", "x",  "y",  "z",  "qw", "qx", "qy", "qz",
    "vx", "vy",   "vz", "wx", "wy", "wz", "cx", "cy", "cz"};

/// The columns of steps.csv, in file order (physics::StepRecord; times in ms of wall clock).
inline constexpr std::array<std::string_view, 11> kStepColumns = {"t",
                                                                  "step",
                                                                  "compute_ms",
                                                                  "sim_contacts",
                                                                  "neighbors",
                                                                  "point_contacts",
                                                                  "solver_iterations",
                                                                  "world_step_ms",
                                                                  "ir_ms",
                                                                  "model_ms",
                                                                  "sync_ms"};

/// One CSV column in memory. `integer` columns (counts, step numbers, body ids) fill `integers`,
/// the others `reals`, with the very values the CSV prints (the CSV is lossless, so parsing the
/// file gives back these doubles bit for bit).
struct Column {
  std::string_view name;
  bool integer = false;
  std::vector<double> reals;
  std::vector<std::int64_t> integers;
};

/// Collects what CsvRecorder writes, as columns. The "body" column of bodies() holds world body
/// ids; body_names() maps them to the names bodies.csv prints. Not RT-safe: the engine calls it
/// from its non-RT side, like every Recorder.
class ColumnRecorder final : public physics::Recorder {
 public:
  ColumnRecorder();

  /// Reserves room for a run of `ticks` ticks and `steps` steps (an estimate; columns still grow
  /// past it).
  void Reserve(std::int64_t ticks, std::int64_t steps);

  void OnTick(const ir::TickRecord& tick) override;
  void OnStep(const physics::StepRecord& step, const world::World& world) override;

  /// Columns in kTickColumns / kBodyColumns / kStepColumns order.
  const std::vector<Column>& ticks() const { return ticks_; }

  const std::vector<Column>& bodies() const { return bodies_; }

  const std::vector<Column>& steps() const { return steps_; }

  /// Name of each world body by id, as bodies.csv prints it unquoted ("body<id>" if unnamed).
  /// Empty until the first step.
  const std::vector<std::string>& body_names() const { return body_names_; }

 private:
  std::vector<Column> ticks_, bodies_, steps_;
  std::vector<std::string> body_names_;
};

}  // namespace mrh::report
