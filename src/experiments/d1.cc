// SPDX-License-Identifier: Apache-2.0
// Demo D1 (thesis §4.6.4): a simulated hand sweeps through 80 objects of four
// shapes on a table with the proposed method (scenes/d1.json), in real time; the report gives
// the haptic rate, overruns, physics step times, peak memory and what the objects did.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "d1_impl.h"
#include "experiment_table.h"
#include "experiment_util.h"
#include "experiments_impl.h"
#include "mrh/session/session.h"

namespace mrh::experiments::internal {
namespace {

constexpr double kGravity = 9.81;  // m/s²
// Objects at rest: the session starts from the scene's keyframe "settled" (MuJoCo's soft
// contacts already sunk to their depth, scripts/make-d1-scene.py), so an untouched object moves
// by less than a millimetre and slower than a centimetre per second.
constexpr double kRestDisplacement = 1e-3;  // m
constexpr double kRestSpeed = 0.01;         // m/s
// Acceptance bars for the real-time run.
constexpr double kMinHapticRate = 990.0;    // Hz
constexpr double kMaxOverrunShare = 0.005;  // of ticks
constexpr double kMaxPeakRss = 300.0;       // MB
// The session's hand path takes this long; --full repeats it, with a second at the top to go
// back to its start.
constexpr double kPathPeriod = 10.0;   // s
constexpr double kCyclePeriod = 11.0;  // s

// scenes/d1.json with the mode and duration set and, for runs longer than one path, the hand's
// keyframes repeated every kCyclePeriod.
nlohmann::json D1Json(bool realtime, double duration) {
  nlohmann::json j = nlohmann::json::parse(ReadText(ScenesDir() / "d1.json"));
  j["mode"] = realtime ? "realtime" : "lockstep";
  j["duration"] = duration;
  const nlohmann::json path = j["device"]["keyframes"];
  nlohmann::json keys = nlohmann::json::array();
  for (int cycle = 0; cycle * kCyclePeriod < duration; ++cycle) {
    for (nlohmann::json k : path) {
      k[0] = k[0].get<double>() + cycle * kCyclePeriod;
      keys.push_back(k);
    }
  }
  j["device"]["keyframes"] = keys;
  return j;
}

session::Session Parse(const nlohmann::json& j, const std::string& origin) {
  return session::ParseSession(j.dump(), ScenesDir(), {}, origin);
}

// The same scene with the hand held still at its start, 20 cm above the table: nothing touches
// the objects.
session::Session RestSession(double duration) {
  nlohmann::json j = D1Json(/*realtime=*/false, duration);
  nlohmann::json pose = j["device"]["keyframes"][0];
  pose.erase(pose.begin());  // t
  j["device"] = {{"type", "fixed"}, {"pose", pose}, {"limits", j["device"]["limits"]}};
  return Parse(j, "d1.json (hand held above the table)");
}

// Speed bound for the objects (m/s), from what can move them. Only the pointer puts energy in:
// touching at speed v, it gives a free object at most (1 + e) v <= 2 v (its penalty contact is at
// most elastic, e <= 1, and the hand behind it is not slowed); contacts between objects are
// MuJoCo's soft constraints, critically damped (solref damping ratio 1, here and in the local
// model), so a struck object gets no more than the striker's speed. Gravity adds sqrt(2 g h) for
// the largest drop h of any object below its start (tipping over, falling off another object).
double SpeedBound(const D1Run& run) {
  return 2.0 * run.max_contact_hand_speed + std::sqrt(2.0 * kGravity * std::max(0.0, run.max_drop));
}

double HapticLoopRate(const D1Run& run) {
  return run.last_tick_t > 0.0 ? static_cast<double>(run.stats.ticks) / run.last_tick_t : 0.0;
}

double OverrunShare(const D1Run& run) {
  return run.stats.ticks > 0
             ? static_cast<double>(run.stats.overruns) / static_cast<double>(run.stats.ticks)
             : 0.0;
}

// The same hand path with the single-rate reference (B1: the whole world in MuJoCo at 1 ms), in
// lockstep over the path's 10 s: what the objects do when the contact model is MuJoCo's own.
session::Session ReferenceSession() {
  nlohmann::json j = D1Json(/*realtime=*/false, kPathPeriod);
  j["method"] = "single-rate";
  j["physics_dt"] = j["haptic_dt"];
  return Parse(j, "d1.json (single-rate reference)");
}

Checks CheckD1(const D1Run& run, const D1Run& rest, const D1Run* ref, bool realtime,
               double rss_mb) {
  Checks c;
  if (ref != nullptr) {
    c.Add("reference_objects_stay_on_the_table", ref->off_table == 0, ref->off_table, 0);
    c.Add("reference_max_body_speed_within_bound_m_per_s", ref->max_body_speed <= SpeedBound(*ref),
          ref->max_body_speed, SpeedBound(*ref));
  }
  c.Add("rest_objects_stay_put_m", rest.max_displacement <= kRestDisplacement,
        rest.max_displacement, kRestDisplacement);
  c.Add("rest_objects_at_rest_m_per_s", rest.max_body_speed <= kRestSpeed, rest.max_body_speed,
        kRestSpeed);
  c.Add("rest_untouched", rest.contact_ticks == 0 && rest.touched_objects == 0);
  c.Add("objects_stay_on_the_table", run.off_table == 0 && rest.off_table == 0,
        run.off_table + rest.off_table, 0);
  c.Add("hand_touches_objects", run.contact_ticks > 0 && run.touched_objects >= 4,
        run.touched_objects, 4);
  c.Add("max_body_speed_within_bound_m_per_s", run.max_body_speed <= SpeedBound(run),
        run.max_body_speed, SpeedBound(run));
  c.Add("no_faults",
        run.stats.fault_nonfinite_wrench == 0 && run.stats.fault_nonfinite_device == 0);
  c.Add("no_warnings", run.stats.warnings.empty() && rest.stats.warnings.empty(),
        static_cast<double>(run.stats.warnings.size() + rest.stats.warnings.size()), 0);
  c.Add("peak_rss_mb", rss_mb < kMaxPeakRss, rss_mb, kMaxPeakRss);
  if (!realtime) return c;  // timings of a lockstep run say nothing about real time
  c.Add("haptic_rate_hz", HapticLoopRate(run) >= kMinHapticRate, HapticLoopRate(run),
        kMinHapticRate);
  c.Add("overrun_share", OverrunShare(run) <= kMaxOverrunShare, OverrunShare(run),
        kMaxOverrunShare);
  c.Add("step_p99_below_physics_dt_ms", run.stats.step_ms_p99 < run.stats.physics_dt * 1e3,
        run.stats.step_ms_p99, run.stats.physics_dt * 1e3);
  return c;
}

// The run's timing, rates and resources.
nlohmann::json TimingNumbers(const D1Run& run, double rss_mb) {
  const engine::RunStats& s = run.stats;
  return {
      {"mode", settings::ModeName(s.mode)},
      {"objects", run.objects},
      {"physics_dt_ms", s.physics_dt * 1e3},
      {"duration_s", s.sim_time},
      {"wall_time_s", s.wall_time},
      {"ticks", s.ticks},
      {"steps", s.steps},
      {"haptic_rate_hz", HapticLoopRate(run)},
      {"engine_haptic_rate_hz", s.haptic_rate_hz},
      {"overruns", s.overruns},
      {"overrun_share", OverrunShare(run)},
      {"jitter_p99_us", s.jitter_p99_us},
      {"step_p50_ms", s.step_ms_p50},
      {"step_p99_ms", s.step_ms_p99},
      {"step_max_ms", s.step_ms_max},
      {"peak_rss_mb", rss_mb},
      {"warnings", s.warnings},
      {"realtime_priority", s.realtime_priority},
  };
}

// What the hand and the objects did in the run, and the objects at rest.
nlohmann::json MotionNumbers(const D1Run& run, const D1Run& rest) {
  const engine::RunStats& s = run.stats;
  return {
      {"max_body_speed_m_per_s", run.max_body_speed},
      {"fastest_body", run.fastest_body},
      {"fastest_t_s", run.fastest_t},
      {"max_hand_speed_m_per_s", run.max_hand_speed},
      {"max_contact_hand_speed_m_per_s", run.max_contact_hand_speed},
      {"max_drop_m", run.max_drop},
      {"speed_bound_m_per_s", SpeedBound(run)},
      {"touched_objects", run.touched_objects},
      {"contact_ticks", run.contact_ticks},
      {"off_table", run.off_table},
      {"first_off_table", run.first_off_table},
      {"max_force_n", s.max_force},
      {"dropped_tick_records", s.dropped_tick_records},
      {"rest_max_displacement_m", rest.max_displacement},
      {"rest_max_speed_m_per_s", rest.max_body_speed},
  };
}

// summary.json's numbers (one object: its keys sort as any nlohmann::json's).
nlohmann::json Numbers(const D1Run& run, const D1Run& rest, const D1Run* ref, double rss_mb) {
  nlohmann::json n = TimingNumbers(run, rss_mb);
  n.update(MotionNumbers(run, rest));
  if (ref != nullptr) {
    n["reference_method"] = ref->stats.method;
    n["reference_max_body_speed_m_per_s"] = ref->max_body_speed;
    n["reference_fastest_body"] = ref->fastest_body;
    n["reference_speed_bound_m_per_s"] = SpeedBound(*ref);
    n["reference_off_table"] = ref->off_table;
    n["reference_first_off_table"] = ref->first_off_table;
  }
  return n;
}

std::string StepsCsv(const D1Run& run) {
  Table t({"t", "step_ms", "sim_contacts", "neighbors", "max_body_speed", "hand_speed",
           "contact_ticks"});
  for (const D1Step& s : run.steps) {
    t.AddFormatted("{:.3f},{:.4f},{},{},{:.5f},{:.5f},{}", s.t, s.step_ms, s.sim_contacts,
                   s.neighbors, s.max_body_speed, s.hand_speed, s.contact_ticks);
  }
  return t.Csv();
}

std::string Markdown(const nlohmann::json& n, const Checks& checks) {
  Table t({"quantity", "value"});
  for (const auto& [key, value] : n.items()) {
    t.Add({key, value.is_number_float()
                    ? fmt::format("{:.4g}", value.get<double>())
                    : (value.is_string() ? value.get<std::string>() : value.dump())});
  }
  return "# D1: 80 objects under the hand (local-dynamics)\n\n" + t.Markdown() + "\n" +
         checks.Markdown();
}

void PlotD1(const std::filesystem::path& out, double physics_dt_ms, double bound, bool quiet) {
  Plot(out, "d1",
       fmt::format(
           "# D1: physics step time and speeds over the run. gnuplot d1.gp\n"
           "set terminal pngcairo size 1000,700 enhanced font ',10'\nset output 'd1.png'\n"
           "set datafile separator ','\nset key autotitle columnhead\nset grid\n"
           "set multiplot layout 2,1\nset ylabel 'physics step (ms)'\n"
           "plot 'd1.csv' using 1:2 with impulses title 'step wall time', {} with lines dt 2 "
           "lw 2 title 'physics\\_dt'\n"
           "set xlabel 'time (s)'\nset ylabel 'speed (m/s)'\n"
           "plot 'd1.csv' using 1:5 with lines title 'fastest object', '' using 1:6 with lines "
           "title 'hand', {} with lines dt 2 title 'bound'\nunset multiplot\n",
           physics_dt_ms, bound),
       quiet);
}

}  // namespace

int RunD1(const std::filesystem::path& out, bool quiet) {
  return RunD1(out, quiet, D1Options{});
}

int RunD1Full(const std::filesystem::path& out, bool quiet) {
  D1Options o;
  o.duration = 60.0;
  return RunD1(out, quiet, o);
}

int RunD1(const std::filesystem::path& out, bool quiet, const D1Options& o) {
  std::filesystem::create_directories(out);
  if (!quiet) std::cout << "d1: objects at rest under a still hand (lockstep)...\n";
  const D1Run rest = RunD1Session(RestSession(o.rest_duration));
  if (!quiet) {
    std::cout << fmt::format("d1: the hand sweeps through them, {} s {}...\n", o.duration,
                             o.realtime ? "in real time" : "in lockstep");
  }
  const D1Run run = RunD1Session(Parse(D1Json(o.realtime, o.duration), "d1.json"));
  const double rss_mb = PeakRssMb();  // before the reference: the demo's own peak
  std::optional<D1Run> ref;
  if (o.reference) {
    if (!quiet) std::cout << "d1: the same path with the single-rate reference (lockstep)...\n";
    ref = RunD1Session(ReferenceSession());
  }
  const D1Run* r = ref ? &*ref : nullptr;
  const Checks checks = CheckD1(run, rest, r, o.realtime, rss_mb);
  const nlohmann::json numbers = Numbers(run, rest, r, rss_mb);
  WriteText(out / "d1.csv", StepsCsv(run));
  WriteText(out / "d1.md", Markdown(numbers, checks));
  PlotD1(out, run.stats.physics_dt * 1e3, SpeedBound(run), quiet);
  if (!quiet) std::cout << numbers.dump(2) << "\n";
  nlohmann::json summary = {{"experiment", "d1"}, {"machine", MachineTag()}, {"d1", numbers}};
  return FinishExperiment(out, std::move(summary), checks, quiet);
}

}  // namespace mrh::experiments::internal
