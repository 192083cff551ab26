// SPDX-License-Identifier: Apache-2.0
// ColumnRecorder: the fields CsvRecorder prints, appended to one vector per column.
#include "mrh/report/column_recorder.h"

#include <algorithm>
#include <span>

#include "mrh/world/world.h"

namespace mrh::report {
namespace {

// Columns named after `names`; those in `integer_names` hold integers.
std::vector<Column> MakeColumns(std::span<const std::string_view> names,
                                std::span<const std::string_view> integer_names) {
  std::vector<Column> columns;
  for (const std::string_view name : names) {
    Column c;
    c.name = name;
    for (const std::string_view i : integer_names) c.integer = c.integer || name == i;
    columns.push_back(std::move(c));
  }
  return columns;
}

constexpr std::array<std::string_view, 2> kTickIntegers = {"contacts", "safety"};
constexpr std::array<std::string_view, 1> kBodyIntegers = {"body"};
constexpr std::array<std::string_view, 5> kStepIntegers = {"step", "sim_contacts", "neighbors",
                                                           "point_contacts", "solver_iterations"};

// Appends `values` to the columns in order, each to the vector its type selects.
template <typename... T>
void AppendRow(std::vector<Column>& columns, T... values) {
  std::size_t i = 0;
  const auto append = [&](auto v) {
    Column& c = columns[i++];
    if (c.integer) {
      c.integers.push_back(static_cast<std::int64_t>(v));
    } else {
      c.reals.push_back(static_cast<double>(v));
    }
  };
  (append(values), ...);
}

void ReserveAll(std::vector<Column>& columns, std::size_t rows) {
  for (Column& c : columns) (c.integer ? c.integers.reserve(rows) : c.reals.reserve(rows));
}

}  // namespace

ColumnRecorder::ColumnRecorder()
    : ticks_(MakeColumns(kTickColumns, kTickIntegers)),
      bodies_(MakeColumns(kBodyColumns, kBodyIntegers)),
      steps_(MakeColumns(kStepColumns, kStepIntegers)) {}

void ColumnRecorder::Reserve(std::int64_t ticks, std::int64_t steps) {
  ReserveAll(ticks_, static_cast<std::size_t>(std::max<std::int64_t>(ticks, 0)));
  ReserveAll(steps_, static_cast<std::size_t>(std::max<std::int64_t>(steps, 0)));
}

void ColumnRecorder::OnTick(const ir::TickRecord& tick) {
  const Pose& X = tick.X_WP;
  const Wrench& w = tick.displayed_W;
  AppendRow(ticks_, tick.t, X.p.x(), X.p.y(), X.p.z(), X.q.w(), X.q.x(), X.q.y(), X.q.z(), w.f.x(),
            w.f.y(), w.f.z(), w.tau.x(), w.tau.y(), w.tau.z(), tick.contacts, tick.safety_bits);
}

void ColumnRecorder::OnStep(const physics::StepRecord& step, const world::World& world) {
  AppendRow(steps_, step.t, step.step, step.compute_ms, step.sim_contacts, step.neighbors,
            step.point_contacts, step.solver_iterations, step.world_step_ms, step.ir_ms,
            step.model_ms, step.sync_ms);
  if (body_names_.empty()) {
    for (int id = 0; id < world.num_bodies(); ++id) {
      const std::string& name = world.body(id).name;
      body_names_.push_back(name.empty() ? "body" + std::to_string(id) : name);
    }
  }
  for (int id = 0; id < world.num_bodies(); ++id) {
    if (world.body(id).is_static) continue;
    const world::BodyState s = world.body_state(id);
    AppendRow(bodies_, step.t, id, s.X_WB.p.x(), s.X_WB.p.y(), s.X_WB.p.z(), s.X_WB.q.w(),
              s.X_WB.q.x(), s.X_WB.q.y(), s.X_WB.q.z(), s.V_WCm.v.x(), s.V_WCm.v.y(), s.V_WCm.v.z(),
              s.V_WCm.w.x(), s.V_WCm.w.y(), s.V_WCm.w.z(), s.p_WCm.x(), s.p_WCm.y(), s.p_WCm.z());
  }
}

}  // namespace mrh::report
