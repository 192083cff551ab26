// SPDX-License-Identifier: Apache-2.0
// Experiment t4.push: a scripted pointer pushes resting boxes across a floor with
// friction at 0.1 m/s; every method against single-rate (the 1 ms reference).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "experiment_table.h"
#include "experiment_util.h"
#include "experiments_impl.h"
#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::experiments::internal {
namespace {

constexpr double kSpeed = 0.1;       // m/s, pointer along +x
constexpr double kX0 = -0.165;       // m, pointer centre at t = 0 (touches the box at t = 1 s)
constexpr double kFrom = 2.0;        // s, statistics window (the acceptance window, 2–5 s)
constexpr double kTo = 5.0;          // s
constexpr double kPositionAt = 5.0;  // s, box position compared 4 s after the touch
constexpr const char* kPerturbation = "local-dynamics/perturbation";

struct Tap final : physics::Recorder {
  void OnTick(const ir::TickRecord& tick) override {
    t.push_back(tick.t);
    f.push_back(tick.rendered_W.f.norm());
  }

  void OnStep(const physics::StepRecord& step, const world::World& world) override {
    if (box < 0) box = world.FindBody("box");
    const world::BodyState s = world.body_state(box);
    steps.push_back({step.t, s.p_WCm, s.V_WCm.w.norm()});
  }

  struct Step {
    double t;
    Vec3 p;
    double spin;
  };

  int box = -1;
  std::vector<double> t, f;
  std::vector<Step> steps;
};

session::Session MakeSession(const PushCase& c, const std::string& variant) {
  nlohmann::json j;
  j["scene"] = "t4_push_" + (c.scene.empty() ? c.name : c.scene) + ".xml";
  j["method"] = variant == kPerturbation ? "local-dynamics" : variant;
  j["physics_dt"] = 0.02;
  j["haptic_dt"] = 0.001;
  j["duration"] = c.duration;
  j["pointer"] = {{"body", "pointer"}, {"radius", 0.015}};
  j["rendering"] = {{"stiffness", 2000.0}, {"damping", 5.0}};
  if (variant == kPerturbation) j["rendering"]["local_model"] = "perturbation";
  const double x_end = kX0 + kSpeed * c.push_until;
  const double yy = c.y;
  nlohmann::json frames = {{0.0, kX0, yy, c.z, 1, 0, 0, 0},
                           {c.push_until, x_end, yy, c.z, 1, 0, 0, 0}};
  if (c.duration > c.push_until) frames.push_back({c.duration, x_end, yy, c.z, 1, 0, 0, 0});
  j["device"] = {{"type", "scripted"}, {"keyframes", frames}};
  return session::ParseSession(j.dump(), ScenesDir(), {},
                               fmt::format("t4.push {} ({})", c.name, variant));
}

PushResult Analyze(const Tap& tap) {
  PushResult r;
  double sum = 0.0, sum2 = 0.0;
  int n = 0, lost = 0;
  for (std::size_t i = 0; i < tap.t.size(); ++i) {
    if (tap.t[i] < kFrom || tap.t[i] > kTo) continue;
    sum += tap.f[i];
    sum2 += tap.f[i] * tap.f[i];
    lost += tap.f[i] <= 0.0 ? 1 : 0;
    ++n;
  }
  r.mean_force = n > 0 ? sum / n : 0.0;
  r.sd_force = n > 1 ? std::sqrt(std::max(0.0, sum2 / n - r.mean_force * r.mean_force)) : 0.0;
  r.contact_lost = n > 0 ? static_cast<double>(lost) / n : 1.0;
  for (const Tap::Step& s : tap.steps) {
    r.peak_spin = std::max(r.peak_spin, s.spin);
    if (s.t <= kPositionAt + 1e-9) r.position = s.p;
  }
  return r;
}

void WriteRun(const std::filesystem::path& dir, const std::string& slug, const Tap& tap) {
  Table f({"t", "force_N"});
  for (std::size_t i = 0; i < tap.t.size(); ++i)
    f.AddFormatted("{:.3f},{:.5f}", tap.t[i], tap.f[i]);
  WriteText(dir / (slug + "_force.csv"), f.Csv());
  Table b({"t", "x", "y", "z", "spin"});
  for (const Tap::Step& s : tap.steps) {
    b.AddFormatted("{:.3f},{:.6f},{:.6f},{:.6f},{:.5f}", s.t, s.p.x(), s.p.y(), s.p.z(), s.spin);
  }
  WriteText(dir / (slug + "_box.csv"), b.Csv());
}

std::string PushScript(const PushOptions& o) {
  std::string gp =
      "# t4.push: |f|(t) per method and the box trajectory, per case. gnuplot t4_push.gp\n"
      "set terminal pngcairo size 1400," +
      std::to_string(330 * o.cases.size()) +
      " enhanced font ',9'\nset output 't4_push.png'\nset datafile separator ','\nset grid\n"
      "set key top left\nset multiplot layout " +
      std::to_string(o.cases.size()) + ",2\n";
  for (const PushCase& c : o.cases) {
    gp += "set title '" + c.name + ": |f| (N)'\nset xlabel 't (s)'\nplot ";
    for (std::size_t i = 0; i < o.methods.size(); ++i) {
      gp += fmt::format("{}'runs/{}_{}_force.csv' using 1:2 with lines title '{}'", i ? ", " : "",
                        c.name, Slug(o.methods[i], '_'), o.methods[i]);
    }
    gp += "\nset title '" + c.name + ": box x (m)'\nplot ";
    for (std::size_t i = 0; i < o.methods.size(); ++i) {
      gp += fmt::format("{}'runs/{}_{}_box.csv' using 1:2 with lines title '{}'", i ? ", " : "",
                        c.name, Slug(o.methods[i], '_'), o.methods[i]);
    }
    gp += "\n";
  }
  return gp + "unset multiplot\n";
}

// The acceptance bars for local-dynamics against single-rate.
bool MeetsBars(const PushResult& r, const PushResult& ref) {
  const bool mean = std::abs(r.mean_force - ref.mean_force) <= 0.05 * ref.mean_force;
  const bool sd = r.sd_force <= std::max(2.0 * ref.sd_force, 0.02 * ref.mean_force);
  const bool lost = r.contact_lost <= ref.contact_lost;
  const bool pos = (r.position - ref.position).norm() <= 0.02;
  return mean && sd && lost && pos;
}

}  // namespace

PushOptions DefaultPushOptions() {
  PushOptions o;
  // The scenes use the elliptic cone (isotropic Coulomb friction). The box_pyramidal cases are
  // the one box with MuJoCo's default pyramidal cone, reported, not held to the bars: there a
  // straight push is an unstable equilibrium, and 10 um of lateral pointer offset turns the
  // single-rate box away (check pyramidal_push_single_rate_is_unstable). row_guided is the row
  // between rails 3 mm clear of its sides; the row's probes show it is not sensitive.
  o.cases = {{"box", 0.05, 6.0, 6.0, 0.0, true, ""},
             {"heavy", 0.05, 6.0, 6.0, 0.0, true, ""},
             {"row", 0.05, 6.0, 6.0, 0.0, true, ""},
             {"row_y+10um", 0.05, 6.0, 6.0, 1e-5, true, "row"},
             {"row_y-10um", 0.05, 6.0, 6.0, -1e-5, true, "row"},
             {"row_guided", 0.05, 6.0, 6.0, 0.0, true, ""},
             {"wall", 0.05, 2.2, 6.0, 0.0, true, ""},
             {"tip", 0.09, 6.0, 6.0, 0.0, true, ""},
             {"box_pyramidal", 0.05, 6.0, 6.0, 0.0, false, ""},
             {"box_pyramidal_y+10um", 0.05, 6.0, 6.0, 1e-5, false, "box_pyramidal"}};
  return o;
}

std::vector<std::vector<PushResult>> RunPushCases(const std::filesystem::path& out,
                                                  const PushOptions& o, bool quiet) {
  std::filesystem::create_directories(out / "runs");
  std::vector<std::vector<PushResult>> results;
  for (const PushCase& c : o.cases) {
    results.emplace_back();
    for (const std::string& m : o.methods) {
      if (!quiet) std::cout << "t4.push: " << c.name << " / " << m << "...\n";
      auto engine = session::MakeEngine(MakeSession(c, m));
      Tap tap;
      engine->Run(&tap);
      WriteRun(out / "runs", c.name + "_" + Slug(m, '_'), tap);
      results.back().push_back(Analyze(tap));
    }
  }
  return results;
}

int RunT4Push(const std::filesystem::path& out, bool quiet) {
  return RunT4Push(out, quiet, DefaultPushOptions());
}

namespace {

// t4_push.csv and t4_push.md: a row per case × method.
struct PushTables {
  Table csv{{"case", "method", "mean_force_N", "mean_vs_single_rate", "sd_force_N", "sd_ratio",
             "contact_lost", "position_error_m", "peak_spin_radps"}};
  Table md{{"case", "method", "mean |f| (N)", "vs single-rate", "sd (N)", "sd ratio",
            "contact lost", "pos. error at 5 s (m)", "peak spin (rad/s)"}};
};

// One case × method against the case's single-rate run `ref`; returns whether it meets the bars.
bool Compare(const std::string& name, const std::string& method, const PushResult& r,
             const PushResult& ref, PushTables* tables, nlohmann::json* summary) {
  const double rel = r.mean_force / ref.mean_force - 1.0;
  const double sd_ratio = ref.sd_force > 0.0 ? r.sd_force / ref.sd_force : 0.0;
  const double err = (r.position - ref.position).norm();
  const bool bars = MeetsBars(r, ref);
  tables->csv.AddFormatted("{},{},{:.4f},{:.4f},{:.4f},{:.3f},{:.4f},{:.4f},{:.3f}", name, method,
                           r.mean_force, rel, r.sd_force, sd_ratio, r.contact_lost, err,
                           r.peak_spin);
  tables->md.Add({name, method, fmt::format("{:.3f}", r.mean_force),
                  fmt::format("{:+.1f} %", 100 * rel), fmt::format("{:.3f}", r.sd_force),
                  fmt::format("{:.2f}", sd_ratio), fmt::format("{:.1f} %", 100 * r.contact_lost),
                  fmt::format("{:.4f}", err), fmt::format("{:.2f}", r.peak_spin)});
  (*summary)["cases"][name][method] = {
      {"mean_force_N", r.mean_force},   {"mean_vs_single_rate", rel},
      {"sd_force_N", r.sd_force},       {"sd_ratio", sd_ratio},
      {"contact_lost", r.contact_lost}, {"position_error_m", err},
      {"peak_spin_radps", r.peak_spin}, {"meets_bars", bars}};
  return bars;
}

// The pyramidal box's single-rate reference at the pointer offsets of its cases (scene
// "box_pyramidal"): the largest spread of the box position at 5 s and of the mean force between
// them. More than the 2 cm position bar: a straight push on MuJoCo's pyramidal cone is
// unstable, and no method can be held to the bars there (check
// pyramidal_push_single_rate_is_unstable; it fails if the reference became reproducible).
void AddInstabilityCheck(const PushOptions& o, const std::vector<std::vector<PushResult>>& results,
                         Checks* checks, nlohmann::json* summary) {
  std::vector<const PushResult*> refs;
  for (std::size_t ci = 0; ci < o.cases.size(); ++ci) {
    const PushCase& c = o.cases[ci];
    if (c.name == "box_pyramidal" || c.scene == "box_pyramidal") refs.push_back(&results[ci][0]);
  }
  if (refs.size() < 2) return;
  double position = 0.0, mean = 0.0;
  for (const PushResult* a : refs) {
    for (const PushResult* b : refs) {
      position = std::max(position, (a->position - b->position).norm());
      mean = std::max(mean, std::abs(a->mean_force / b->mean_force - 1.0));
    }
  }
  (*summary)["pyramidal_single_rate_spread"] = {{"position_m", position}, {"mean_force", mean}};
  checks->Add("pyramidal_push_single_rate_is_unstable", position > 0.02);
}

}  // namespace

int RunT4Push(const std::filesystem::path& out, bool quiet, const PushOptions& o) {
  const auto results = RunPushCases(out, o, quiet);
  nlohmann::json summary;
  PushTables tables;
  Checks checks;
  for (std::size_t ci = 0; ci < o.cases.size(); ++ci) {
    const PushResult& ref = results[ci][0];  // methods[0] is single-rate
    for (std::size_t mi = 0; mi < o.methods.size(); ++mi) {
      const bool bars =
          Compare(o.cases[ci].name, o.methods[mi], results[ci][mi], ref, &tables, &summary);
      if (o.methods[mi] == "local-dynamics" && o.cases[ci].checked) {
        checks.Add("local_dynamics_meets_bars_" + o.cases[ci].name, bars);
      }
    }
  }
  AddInstabilityCheck(o, results, &checks, &summary);
  WriteText(out / "t4_push.csv", tables.csv.Csv());
  WriteText(out / "t4_push.md", tables.md.Markdown());
  Plot(out, "t4_push", PushScript(o), quiet);
  summary["experiment"] = "t4.push";
  summary["machine"] = MachineTag();
  summary["window_s"] = {kFrom, kTo};
  if (!quiet) std::cout << tables.md.Markdown();
  return FinishExperiment(out, std::move(summary), checks, quiet);
}

}  // namespace mrh::experiments::internal
