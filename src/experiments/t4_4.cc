// SPDX-License-Identifier: Apache-2.0
// Experiment T4.4 (thesis §4.6.1): the accelerance includes the bodies the pushed cube touches.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "experiment_table.h"
#include "experiment_util.h"
#include "experiments_impl.h"
#include "mrh/core/error.h"
#include "mrh/engine/engine.h"
#include "mrh/ir/snapshot.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::experiments::internal {
namespace {

// scenes/t4_4.xml: 2 kg cubes; cube2..4 join at t = 1, 2, 3 s under the pointer's constant
// acceleration from rest; the edge cube is pushed 4 cm off its centre line.
constexpr double kCubeMass = 2.0;     // kg
constexpr double kHalf = 0.05;        // m
constexpr double kAccel = 0.1;        // m/s², pointer
constexpr double kX0 = -0.07;         // m, pointer centre touching cube1 / edge_cube at t = 0
constexpr double kZ = 0.049755;       // m, settled cube centre height (keyframe "settled")
constexpr double kEdgeY = 1.0;        // m, edge_cube centre
constexpr double kEdgeOffset = 0.04;  // m, pointer line above the edge cube's centre line
// The last window runs to the end: the fourth join (at 0.3 m/s) kicks the group off the pointer
// for about 0.4 s in every method, so it needs more time after the join than the others.
constexpr double kLineDuration = 5.0;  // s
constexpr double kEdgeDuration = 1.5;  // s
constexpr double kKeyframeDt = 0.005;  // s, dense keyframes approximate the parabola
constexpr int kCubes = 4;
// Windows: after each join, wait this long for the collision transient, and stop this long before
// the next join.
constexpr double kSettle = 0.5;  // s
constexpr double kGuard = 0.05;  // s
// Acceptance: felt mass within 5 % of k·m ("within a few %").
constexpr double kMassTolerance = 0.05;
constexpr const char* kNoPerturbation = "local-dynamics/no-perturbation";

struct StepState {
  double t = 0.0;
  Vec3 v1 = Vec3::Zero();    // cube1 COM velocity (m/s)
  double edge_wz = 0.0;      // edge_cube ω_z (rad/s)
  double edge_yaw = 0.0;     // edge_cube rotation about z (rad)
  double edge_vx = 0.0;      // edge_cube v_x (m/s)
  double felt_mass_A = 0.0;  // 1 / A_xx of cube1 in the snapshot (kg), 0 if none
};

class Tap final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& tick) override {
    t.push_back(tick.t);
    f.push_back(tick.rendered_W.f);
  }

  void OnStep(const physics::StepRecord& step, const world::World& world) override {
    if (cube1_ < 0) {
      cube1_ = world.FindBody("cube1");
      edge_ = world.FindBody("edge_cube");
    }
    const world::BodyState c1 = world.body_state(cube1_), e = world.body_state(edge_);
    const Vec3 x_axis = e.X_WB.q * Vec3::UnitX();
    steps.push_back({step.t, c1.V_WCm.v, e.V_WCm.w.z(), std::atan2(x_axis.y(), x_axis.x()),
                     e.V_WCm.v.x(), 0.0});
  }

  std::vector<double> t;
  std::vector<Vec3> f;  // force on the hand, world (N)
  std::vector<StepState> steps;

 private:
  int cube1_ = -1, edge_ = -1;
};

// Pointer keyframes x(t) = kX0 + ½·a·t² (dense, so the velocity steps are tiny).
nlohmann::json Keyframes(double y, double duration) {
  nlohmann::json frames = nlohmann::json::array();
  const auto n = static_cast<int>(std::llround(duration / kKeyframeDt));
  for (int i = 0; i <= n; ++i) {
    const double t = i * kKeyframeDt;
    frames.push_back({t, kX0 + 0.5 * kAccel * t * t, y, kZ, 1, 0, 0, 0});
  }
  return frames;
}

session::Session MakeSession(const std::string& variant, const std::string& method, bool edge) {
  std::ifstream in(ScenesDir() / "t4_4.json");
  nlohmann::json json = nlohmann::json::parse(in);
  json["method"] = method;
  json["duration"] = edge ? kEdgeDuration : kLineDuration;
  json["device"]["keyframes"] =
      edge ? Keyframes(kEdgeY + kEdgeOffset, kEdgeDuration) : Keyframes(0.0, kLineDuration);
  if (variant == kNoPerturbation) json["rendering"]["perturbation"] = false;
  // T4.4 measures the thesis' accelerance A (the contact local model has none).
  json["rendering"]["local_model"] = "perturbation";
  return session::ParseSession(json.dump(), ScenesDir(), {}, "scenes/t4_4.json (" + variant + ")");
}

struct RunData {
  Tap tap;
  double physics_dt = 0.0, haptic_dt = 0.0;
};

// One run of a variant, recording the snapshot's accelerance of cube1 through the timed wrapper.
RunData Run(const std::string& variant, bool edge) {
  // Shared with the registered wrapper, which outlives this call: no references to locals.
  struct Observed {
    int cube1 = -1;
    std::vector<double> felt_A;  // 1 / A_xx of cube1 per snapshot (kg), 0 if none
  };

  const auto observed = std::make_shared<Observed>();
  const auto timings = std::make_shared<MethodTimings>();
  timings->on_snapshot = [observed](const ir::PhysicsSnapshot& s) {
    double m = 0.0;
    for (const ir::BodyMotion& b : s.bodies) {
      if (b.body == observed->cube1 && b.has_dynamics && b.A(0, 0) > 0.0) m = 1.0 / b.A(0, 0);
    }
    observed->felt_A.push_back(m);
  };
  const std::string inner = variant == kNoPerturbation ? "local-dynamics" : variant;
  const std::string method = RegisterTimedMethod(inner, timings, 0, 0);
  auto engine = session::MakeEngine(MakeSession(variant, method, edge));
  observed->cube1 = engine->world().FindBody("cube1");
  RunData data;
  engine->Run(&data.tap);
  for (std::size_t i = 0; i < data.tap.steps.size() && i < observed->felt_A.size(); ++i) {
    data.tap.steps[i].felt_mass_A = observed->felt_A[i];
  }
  data.physics_dt = engine->settings().physics_dt;
  data.haptic_dt = engine->settings().haptic_dt;
  return data;
}

struct Window {
  int cubes = 0;
  double t_a = 0.0, t_b = 0.0;  // s, step times bounding the window
  double force = 0.0;           // N, mean push force over the window
  double accel = 0.0;           // m/s², cube1's mean acceleration over the window
  double felt_mass = 0.0;       // kg, force / accel
  double felt_mass_A = 0.0;     // kg, median 1/A_xx of the snapshots in the window (0: none)
};

// Felt mass per window. The world's velocity at a step's end reflects the user's force only up
// to one physics period earlier (every method hands the period's force to the next step), so
// the force is averaged over the window shifted back by one period.
std::vector<Window> FeltMass(const RunData& run) {
  std::vector<Window> windows;
  const std::vector<StepState>& s = run.tap.steps;
  for (int k = 1; k <= kCubes; ++k) {
    Window w;
    w.cubes = k;
    const double from = (k - 1) + kSettle, to = (k < kCubes ? k : kLineDuration) - kGuard;
    const StepState *a = nullptr, *b = nullptr;
    std::vector<double> masses_A;
    for (const StepState& st : s) {
      if (st.t >= from - 1e-9 && a == nullptr) a = &st;
      if (st.t <= to + 1e-9) b = &st;
      if (st.t >= from - 1e-9 && st.t <= to + 1e-9 && st.felt_mass_A > 0.0) {
        masses_A.push_back(st.felt_mass_A);
      }
    }
    if (a == nullptr || b == nullptr || b->t <= a->t) continue;
    w.t_a = a->t;
    w.t_b = b->t;
    double impulse = 0.0;
    const double lag = run.physics_dt;
    for (std::size_t i = 0; i < run.tap.t.size(); ++i) {
      const double t = run.tap.t[i];
      if (t >= w.t_a - lag - 1e-9 && t < w.t_b - lag - 1e-9) {
        impulse -= run.tap.f[i].x() * run.haptic_dt;
      }
    }
    w.force = impulse / (w.t_b - w.t_a);
    w.accel = (b->v1.x() - a->v1.x()) / (w.t_b - w.t_a);
    w.felt_mass = w.accel != 0.0 ? w.force / w.accel : 0.0;
    if (!masses_A.empty()) {
      // Median: the snapshots right after a contact is lost or regained are outliers.
      std::nth_element(masses_A.begin(), masses_A.begin() + masses_A.size() / 2, masses_A.end());
      w.felt_mass_A = masses_A[masses_A.size() / 2];
    }
    windows.push_back(w);
  }
  return windows;
}

struct EdgeResult {
  double wz_end = 0.0;       // rad/s, edge_cube ω_z at the end
  double yaw_end = 0.0;      // rad
  double ratio_early = 0.0;  // ω_z / v_x at the first step after kEdgeEarly (rad/m)
};

// Early in the edge push the cube has barely turned, so ω_z / v_x = −y·m / I_zz (1/m) for a force
// along x at lever y on a free cube (I_zz = m·(2h)²/6 for a cube of side 2h).
constexpr double kEdgeEarly = 0.3;  // s

double AnalyticEdgeRatio() {
  const double izz = kCubeMass * (2 * kHalf) * (2 * kHalf) / 6.0;
  return -kEdgeOffset * kCubeMass / izz;
}

EdgeResult Edge(const RunData& run) {
  EdgeResult r;
  const std::vector<StepState>& s = run.tap.steps;
  if (s.empty()) return r;
  r.wz_end = s.back().edge_wz;
  r.yaw_end = s.back().edge_yaw;
  for (const StepState& st : s) {
    if (st.t >= kEdgeEarly - 1e-9 && st.edge_vx != 0.0) {
      r.ratio_early = st.edge_wz / st.edge_vx;
      break;
    }
  }
  return r;
}

void WriteRunCsv(const std::filesystem::path& dir, const std::string& variant, const RunData& line,
                 const RunData& edge) {
  Table ticks({"t", "f_cube_x"});
  for (std::size_t i = 0; i < line.tap.t.size(); ++i) {
    ticks.AddFormatted("{:.3f},{:.6f}", line.tap.t[i], -line.tap.f[i].x());
  }
  WriteText(dir / fmt::format("line_{}.csv", Slug(variant)), ticks.Csv());
  Table steps({"t", "cube1_vx", "felt_mass_A_kg"});
  for (const StepState& s : line.tap.steps) {
    steps.AddFormatted("{:.3f},{:.6f},{:.6f}", s.t, s.v1.x(), s.felt_mass_A);
  }
  WriteText(dir / fmt::format("line_steps_{}.csv", Slug(variant)), steps.Csv());
  Table e({"t", "edge_vx", "edge_wz", "edge_yaw"});
  for (const StepState& s : edge.tap.steps) {
    e.AddFormatted("{:.3f},{:.6f},{:.6f},{:.6f}", s.t, s.edge_vx, s.edge_wz, s.edge_yaw);
  }
  WriteText(dir / fmt::format("edge_{}.csv", Slug(variant)), e.Csv());
}

std::string T44Script(const std::vector<std::string>& variants) {
  std::string plot =
      "# T4.4: force on the pushed cube, its accelerance's felt mass, and the edge push.\n"
      "# Re-run with: gnuplot t4_4.gp\n"
      "set terminal pngcairo size 1200,1100 enhanced font ',10'\nset output 't4_4.png'\n"
      "set datafile separator ','\nset grid\nset key top left\nset multiplot layout 3,1\n"
      "set arrow from 1, graph 0 to 1, graph 1 nohead dt 3\n"
      "set arrow from 2, graph 0 to 2, graph 1 nohead dt 3\n"
      "set arrow from 3, graph 0 to 3, graph 1 nohead dt 3\n"
      "set title 'Line push at 0.1 m/s^2: cube2, cube3, cube4 join at t = 1, 2, 3 s "
      "(expected force 0.2, 0.4, 0.6, 0.8 N)'\n"
      "set xlabel 't (s)'\nset ylabel 'force on cube1 (N)'\nset yrange [-0.5:2]\nplot ";
  for (std::size_t i = 0; i < variants.size(); ++i) {
    plot += fmt::format("{}'runs/line_{}.csv' using 1:2 with lines lw 1.5 title '{}'",
                        i == 0 ? "" : ", ", Slug(variants[i]), variants[i]);
  }
  plot +=
      ", (x<1?0.2:x<2?0.4:x<3?0.6:0.8) with lines dt 2 lc 'black' title 'k m a'\n"
      "set title 'Felt mass 1/A_{xx} of cube1 in each snapshot (expected 2, 4, 6, 8 kg)'\n"
      "set ylabel 'kg'\nset yrange [0:10]\nplot ";
  bool first = true;
  for (const std::string& v : variants) {
    if (v.rfind("local-dynamics", 0) != 0) continue;
    plot += fmt::format(
        "{}'runs/line_steps_{}.csv' using 1:($3>0?$3:1/0) with linespoints "
        "title '{}'",
        first ? "" : ", ", Slug(v), v);
    first = false;
  }
  plot +=
      ", (x<1?2:x<2?4:x<3?6:8) with lines dt 2 lc 'black' title 'k m'\n"
      "unset arrow\nset title 'Edge push 4 cm off centre: rotation of the cube'\n"
      "set ylabel 'yaw (rad)'\nset yrange [*:*]\nplot ";
  for (std::size_t i = 0; i < variants.size(); ++i) {
    plot += fmt::format("{}'runs/edge_{}.csv' using 1:4 with lines lw 1.5 title '{}'",
                        i == 0 ? "" : ", ", Slug(variants[i]), variants[i]);
  }
  return plot + "\nunset multiplot\n";
}

// felt_mass.csv, felt_mass.md and edge.md: a row per window / per variant.
struct T44Tables {
  Table csv{{"variant", "cubes", "t_from", "t_to", "force_N", "accel_mps2", "felt_mass_kg",
             "expected_kg", "felt_mass_A_kg"}};
  Table md{{"variant", "cubes", "force (N)", "accel (m/s²)", "felt mass (kg)", "expected (kg)",
            "1/A_xx (kg)"}};
  Table edge_md{{"variant", "ω_z at end (rad/s)", "yaw at end (rad)", "ω_z/v_x early (1/m)",
                 "analytic (1/m)"}};
};

// The line push of one variant: each window's felt mass (from force / acceleration and from
// the snapshot's accelerance) against k·m. Sets *masses_ok and *accelerance_ok.
void LineWindows(const std::string& variant, const RunData& line, T44Tables* tables,
                 nlohmann::json* summary, bool* masses_ok, bool* accelerance_ok) {
  *masses_ok = true;
  *accelerance_ok = true;
  for (const Window& w : FeltMass(line)) {
    const double expected = w.cubes * kCubeMass;
    *masses_ok = *masses_ok && std::abs(w.felt_mass - expected) <= kMassTolerance * expected;
    *accelerance_ok =
        *accelerance_ok && std::abs(w.felt_mass_A - expected) <= kMassTolerance * expected;
    tables->csv.AddFormatted("{},{},{:.3f},{:.3f},{:.6f},{:.6f},{:.4f},{},{:.4f}", variant, w.cubes,
                             w.t_a, w.t_b, w.force, w.accel, w.felt_mass, expected, w.felt_mass_A);
    tables->md.Add({variant, fmt::format("{}", w.cubes), fmt::format("{:.4f}", w.force),
                    fmt::format("{:.4f}", w.accel), fmt::format("{:.3f}", w.felt_mass),
                    fmt::format("{:.0f}", expected), fmt::format("{:.3f}", w.felt_mass_A)});
    (*summary)["felt_mass_kg"].push_back(w.felt_mass);
    (*summary)["felt_mass_A_kg"].push_back(w.felt_mass_A);
  }
  (*summary)["felt_mass_within_5_percent"] = *masses_ok;
  (*summary)["accelerance_within_5_percent"] = *accelerance_ok;
}

// Sign from the lever (τ_z = −y·f_x < 0); size from the free-cube ratio while barely turned.
bool EdgeTurns(const EdgeResult& e) {
  return e.wz_end < 0.0 && e.yaw_end < 0.0 &&
         std::abs(e.ratio_early - AnalyticEdgeRatio()) <= kMassTolerance * -AnalyticEdgeRatio();
}

// Runs one variant's line and edge pushes; the local-dynamics variant adds the checks.
void RunVariant(const std::filesystem::path& out, const std::string& variant, bool quiet,
                T44Tables* tables, nlohmann::json* summary, Checks* checks) {
  if (!quiet) std::cout << "t4.4: " << variant << "...\n";
  const RunData line = Run(variant, false), edge = Run(variant, true);
  WriteRunCsv(out / "runs", variant, line, edge);
  nlohmann::json& v = (*summary)["variants"][variant];
  bool masses_ok = true, accelerance_ok = true;
  LineWindows(variant, line, tables, &v, &masses_ok, &accelerance_ok);
  const EdgeResult e = Edge(edge);
  tables->edge_md.Add({variant, fmt::format("{:.4f}", e.wz_end), fmt::format("{:.4f}", e.yaw_end),
                       fmt::format("{:.2f}", e.ratio_early),
                       fmt::format("{:.2f}", AnalyticEdgeRatio())});
  v["edge"] = {{"wz_end", e.wz_end}, {"yaw_end", e.yaw_end}, {"wz_over_vx_early", e.ratio_early}};
  if (variant == "local-dynamics") {
    checks->Add("local_dynamics_felt_mass_steps_with_each_cube", masses_ok);
    checks->Add("local_dynamics_accelerance_includes_the_pushed_cubes", accelerance_ok);
    checks->Add("local_dynamics_edge_push_turns_the_cube", EdgeTurns(e), e.ratio_early,
                AnalyticEdgeRatio());
  }
}

}  // namespace

int RunT44(const std::filesystem::path& out, bool quiet) {
  return RunT44(out, quiet, T44Options{});
}

int RunT44(const std::filesystem::path& out, bool quiet, const T44Options& options) {
  std::filesystem::create_directories(out / "runs");
  T44Tables tables;
  nlohmann::json summary;
  Checks checks;
  for (const std::string& variant : options.variants) {
    RunVariant(out, variant, quiet, &tables, &summary, &checks);
  }
  WriteText(out / "felt_mass.csv", tables.csv.Csv());
  WriteText(out / "felt_mass.md", tables.md.Markdown());
  WriteText(out / "edge.md", tables.edge_md.Markdown());
  Plot(out, "t4_4", T44Script(options.variants), quiet);
  summary["experiment"] = "t4.4";
  summary["machine"] = MachineTag();
  summary["analytic_edge_wz_over_vx"] = AnalyticEdgeRatio();
  if (!quiet) std::cout << tables.md.Markdown() << "\n" << tables.edge_md.Markdown();
  return FinishExperiment(out, std::move(summary), checks, quiet);
}

}  // namespace mrh::experiments::internal
