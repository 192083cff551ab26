// SPDX-License-Identifier: Apache-2.0
// WriteSummary: every RunStats field as a pretty-printed summary.json.
#include <fmt/format.h>

#include <cerrno>
#include <fstream>
#include <nlohmann/json.hpp>
#include <system_error>

#include "mrh/core/error.h"
#include "mrh/report/report.h"

namespace mrh::report {
namespace {

using json = nlohmann::ordered_json;

json ToJson(const Vec3& v) {
  return json::array({v.x(), v.y(), v.z()});
}

json Faults(const engine::RunStats& s) {
  return json{{"nonfinite_wrench", s.fault_nonfinite_wrench},
              {"nonfinite_device", s.fault_nonfinite_device},
              {"force_clamped", s.force_clamped},
              {"torque_clamped", s.torque_clamped},
              {"watchdog_ticks", s.watchdog_ticks},
              {"dropped_tick_records", s.dropped_tick_records},
              {"dropped_reports", s.dropped_reports},
              {"ir_status", s.ir_status}};
}

json Impulses(const engine::RunStats& s) {
  json out = json::array();
  for (const physics::BodyImpulseTotal& impulse : s.impulses) {
    out.push_back(json{{"body", impulse.body},
                       {"name", impulse.name},
                       {"linear", ToJson(impulse.linear)},
                       {"angular", ToJson(impulse.angular)},
                       {"linear_norm", impulse.linear.norm()}});
  }
  return out;
}

// Ticks per named method status bit, e.g. {"proxy.not_converged": 12}.
json MethodStatus(const engine::RunStats& s) {
  json out = json::object();
  for (const auto& [name, ticks] : s.method_status) out[name] = ticks;
  return out;
}

json DeviceCounters(const device::DeviceCounters& d) {
  return json{{"poses_received", d.poses_received}, {"wrenches_sent", d.wrenches_sent},
              {"pose_timeouts", d.pose_timeouts},   {"packets_malformed", d.packets_malformed},
              {"vendor_errors", d.vendor_errors},   {"torque_dropped", d.torque_dropped}};
}

// Several pointers: one block per pointer, in pointer order.
json Pointers(const engine::RunStats& s) {
  json out = json::array();
  for (const engine::PointerRunStats& p : s.pointers) {
    out.push_back(
        json{{"body", p.body},
             {"max_force", p.max_force},
             {"mean_force", p.mean_force},
             {"max_torque", p.max_torque},
             {"faults",
              {{"nonfinite_wrench", p.fault_nonfinite_wrench},
               {"nonfinite_device", p.fault_nonfinite_device},
               {"force_clamped", p.force_clamped},
               {"torque_clamped", p.torque_clamped},
               {"watchdog_ticks", p.watchdog_ticks}}},
             {"final_wrench",
              {{"force", ToJson(p.final_wrench.f)}, {"torque", ToJson(p.final_wrench.tau)}}},
             {"device", DeviceCounters(p.device)}});
  }
  return out;
}

// Keys mirror the RunStats fields; the three percentile groups are nested objects so that
// scripts read e.g. summary["jitter_us"]["p99"].
json ToJson(const engine::RunStats& s, const std::string& session, const std::string& scene) {
  json out{
      {"session", session},
      {"scene", scene},
      {"method", s.method},
      {"mode", settings::ModeName(s.mode)},
      {"physics_dt", s.physics_dt},
      {"haptic_dt", s.haptic_dt},
      {"sim_time", s.sim_time},
      {"wall_time", s.wall_time},
      {"ticks", s.ticks},
      {"steps", s.steps},
      {"haptic_rate_hz", s.haptic_rate_hz},
      {"physics_rate_hz", s.physics_rate_hz},
      {"overruns", s.overruns},
      {"jitter_us", {{"p50", s.jitter_p50_us}, {"p99", s.jitter_p99_us}, {"max", s.jitter_max_us}}},
      {"step_ms", {{"p50", s.step_ms_p50}, {"p99", s.step_ms_p99}, {"max", s.step_ms_max}}},
      {"max_force", s.max_force},
      {"max_torque", s.max_torque},
      {"faults", Faults(s)},
      {"final_wrench",
       {{"force", ToJson(s.final_wrench.f)},
        {"torque", ToJson(s.final_wrench.tau)},
        {"stopped", s.stopped}}},
      {"realtime_priority", s.realtime_priority},
      {"device", DeviceCounters(s.device)},
      {"impulses", Impulses(s)},
      {"method_status", MethodStatus(s)},
      {"step_phases_ms",
       {{"world_step", s.phase_ms.world_step_ms},
        {"ir", s.phase_ms.ir_ms},
        {"model", s.phase_ms.model_ms},
        {"sync", s.phase_ms.sync_ms}}},
      {"warnings", s.warnings}};
  // Only with several pointers, so that one-pointer summaries keep their keys.
  if (!s.pointers.empty()) out["pointers"] = Pointers(s);
  return out;
}

}  // namespace

std::string SummaryJson(const engine::RunStats& stats, const std::string& session_file,
                        const std::string& scene_file) {
  return ToJson(stats, session_file, scene_file).dump(2) + '\n';
}

void WriteSummary(const std::filesystem::path& dir, const engine::RunStats& stats,
                  const std::string& session_file, const std::string& scene_file) {
  const std::filesystem::path path = dir / "summary.json";
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) {
    throw RuntimeError(fmt::format("cannot open {} for writing: {}; choose a writable --out",
                                   path.string(), std::generic_category().message(errno)));
  }
  file << SummaryJson(stats, session_file, scene_file);
  file.close();
  if (!file) {
    throw RuntimeError(fmt::format("cannot write {}: {}; check free disk space", path.string(),
                                   std::generic_category().message(errno)));
  }
}

}  // namespace mrh::report
