// SPDX-License-Identifier: Apache-2.0
// Experiment t3.7: the 6-DOF methods on ordinary objects (scenes/t3_7_*.xml: sphere, lying
// capsule, upright cylinder, ellipsoid, convex mesh, compound body), pushed centred and off
// centre at 0.1 m/s by a frictionless box or sphere pointer, against a consistent reference — the
// tool as a rigid MuJoCo body at 1 ms (virtual coupling with the rendering's gains) — and against
// what mechanics predicts: a steady slide costs Coulomb's μ m g, a round body rolls at v / r and is
// never thrown faster than a few times the pointer's speed.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <vector>

#include "experiment_table.h"
#include "experiment_util.h"
#include "experiments_impl.h"
#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::experiments::internal {
namespace {

constexpr double kSpeed = 0.1;      // m/s along +x
constexpr double kTouch = 1.0;      // s, the pointer reaches the object
constexpr double kDuration = 5.0;   // s
constexpr double kFrom = 2.0;       // s, statistics window 2–5 s
constexpr double kFriction = 0.5;   // the floor's (scenes/t3_7_*.xml); pointers have none
constexpr double kThrowBar = 2.5;   // the bar: speed ≤ 2.5 v, spin ≤ 2.5 v / r
constexpr double kSlideBar = 0.05;  // steady slide: mean |f| within 5 % of μ m g
constexpr double kForceBar = 0.10;  // off-centre: mean |f| within 10 % of the reference's
constexpr double kPoseBar = 0.02;   // m, off-centre: positions within 2 cm of the reference's
// A turn smaller than this in the reference has no direction worth comparing.
constexpr double kTurnFloor = 5.0 * std::numbers::pi / 180.0;

// Rendering gains shared by every method; the virtual coupling's are matched to them.
constexpr double kStiffness = 2000.0;   // N/m
constexpr double kDamping = 5.0;        // N·s/m
constexpr double kRotStiffness = 20.0;  // N·m/rad
// The coupled tool: the pointers weigh 14 and 48 g; 0.1 kg and 1e-3 kg·m² keep the coupling
// stable at these gains (the rotation needs the inertia) and damped enough not to ring.
constexpr double kToolMass = 0.1;       // kg
constexpr double kToolInertia = 0.001;  // kg·m², each principal moment

enum class Motion { kRolls, kSlides };

struct Shape {
  const char* name;
  double reach;   // m, from the object's centre to its surface toward −x
  double push_z;  // m, pointer height
  Motion motion;
  // m, rolling radius (kRolls): the smallest a rolling body turns on, so v / r bounds its spin.
  double radius;
  // Its side is round about a vertical axis: every contact normal there passes through the
  // axis, so a centred point push cannot turn it.
  bool round_side;
};

// The ellipsoid, pushed at its long end, tips onto it and rolls like an egg: its centre falls
// from 5 to 3 cm each half turn, so gravity, not the push, sets its speed (√(2 g 0.02) = 0.63 m/s).
constexpr Shape kShapes[] = {{"sphere", 0.04, 0.04, Motion::kRolls, 0.04, true},
                             {"capsule", 0.03, 0.03, Motion::kRolls, 0.03, false},
                             {"cylinder", 0.04, 0.04, Motion::kSlides, 0.0, true},
                             {"ellipsoid", 0.05, 0.03, Motion::kRolls, 0.03, false},
                             {"mesh", 0.034641, 0.03, Motion::kSlides, 0.0, false},
                             {"compound", 0.03, 0.03, Motion::kSlides, 0.0, false}};

struct PointerKind {
  const char* name;  // "box" | "sphere"
  const char* body;  // mocap body in every t3.7 scene
  double reach;      // m, from the pointer's origin to its face toward +x
  // m along +y, the off-centre push: the box pointer's face (6 cm wide) then lies wholly on one
  // side of the objects' centre line, so its centre of pressure is off centre.
  double offset;
  // A flat face: pressed square on an object's flat side it holds it straight (the centre of
  // pressure moves to resist a turn), where a point push on a flat side is an unstable
  // equilibrium that turns the object one way or the other.
  bool face;
};

constexpr PointerKind kPointers[] = {{"box", "box_pointer", 0.01, 0.04, true},
                                     {"sphere", "sphere_pointer", 0.015, 0.02, false}};

struct Variant {
  const char* label;
  const char* method;
  double physics_dt;
};

constexpr Variant kVariants[] = {{"virtual-coupling@1ms", "virtual-coupling", 0.001},
                                 {"proxy-6dof@1ms", "proxy-6dof", 0.001},
                                 {"proxy-6dof@20ms", "proxy-6dof", 0.02},
                                 {"local-dynamics-6dof@20ms", "local-dynamics-6dof", 0.02}};

struct Case {
  const Shape* shape;
  const PointerKind* pointer;
  double y;  // m, pointer offset

  std::string Name() const {
    return fmt::format("{}_{}_{}", shape->name, pointer->name, y == 0.0 ? "centred" : "offcentre");
  }
};

session::Session MakeSession(const Case& c, const Variant& v) {
  nlohmann::json j;
  j["scene"] = fmt::format("t3_7_{}.xml", c.shape->name);
  j["method"] = v.method;
  j["physics_dt"] = v.physics_dt;
  j["haptic_dt"] = 0.001;
  j["duration"] = kDuration;
  j["pointer"] = {{"body", c.pointer->body}};
  j["rendering"] = {{"stiffness", kStiffness},
                    {"damping", kDamping},
                    {"rot_stiffness", kRotStiffness},
                    {"friction", 0.0},
                    {"torque_model", "contact"},
                    {"coupling_stiffness", kStiffness},
                    {"coupling_damping", kDamping},
                    {"coupling_rot_stiffness", kRotStiffness},
                    {"tool_mass", kToolMass},
                    {"tool_inertia", {kToolInertia, kToolInertia, kToolInertia}}};
  j["safety"] = {{"ramp", false}};
  const double x0 = -c.shape->reach - c.pointer->reach - kSpeed * kTouch;
  const double x1 = x0 + kSpeed * kDuration;
  j["device"] = {{"type", "scripted"},
                 {"keyframes",
                  {{0.0, x0, c.y, c.shape->push_z, 1, 0, 0, 0},
                   {kDuration, x1, c.y, c.shape->push_z, 1, 0, 0, 0}}}};
  return session::ParseSession(j.dump(), ScenesDir(), {},
                               fmt::format("t3.7 {} ({})", c.Name(), v.label));
}

// Rendered |f| per tick; the object's state per step.
struct Tap final : engine::Recorder {
  void OnTick(const engine::TickRecord& tick) override {
    t.push_back(tick.t);
    f.push_back(tick.rendered_W.f.norm());
    f_W.push_back(tick.rendered_W.f);
  }

  void OnStep(const engine::StepRecord& step, const world::World& world) override {
    if (object < 0) {
      object = world.FindBody("object");
      mass = world.body(object).mass;
      g = world.gravity().norm();
    }
    steps.push_back({step.t, world.body_state(object)});
  }

  struct Step {
    double t;
    world::BodyState state;
  };

  int object = -1;
  double mass = 0.0, g = 0.0;  // kg, m/s²
  std::vector<double> t, f;
  std::vector<Vec3> f_W;
  std::vector<Step> steps;
};

// Heading of the body's x axis about +z (rad): the turn of a body that does not roll.
double Yaw(const Quat& q) {
  const Mat3 R = q.toRotationMatrix();
  return std::atan2(R(1, 0), R(0, 0));
}

T37Result Analyze(const Case& c, const Variant& v, const Tap& tap) {
  T37Result r;
  r.shape = c.shape->name;
  r.pointer = c.pointer->name;
  r.offcentre = c.y != 0.0;
  r.method = v.label;
  // A steady slide, the push Coulomb's μ m g: a centred push that holds the object straight.
  const bool steady = c.y == 0.0 && (c.pointer->face || c.shape->round_side);
  r.coulomb_f = c.shape->motion == Motion::kSlides && steady ? kFriction * tap.mass * tap.g : 0.0;
  r.rolling_radius = c.shape->radius;
  double s = 0.0, ss = 0.0, n = 0.0;
  for (std::size_t i = 0; i < tap.t.size(); ++i) {
    if (tap.t[i] >= kTouch - 0.1 && i > 0) r.impulse += tap.f_W[i] * (tap.t[i] - tap.t[i - 1]);
    if (tap.t[i] < kFrom) continue;
    s += tap.f[i];
    ss += tap.f[i] * tap.f[i];
    n += 1.0;
  }
  r.mean_f = n > 0.0 ? s / n : 0.0;
  r.sd_f = n > 0.0 ? std::sqrt(std::max(0.0, ss / n - r.mean_f * r.mean_f)) : 0.0;
  for (const Tap::Step& step : tap.steps) {
    if (step.t < kTouch - 0.1) continue;  // a 20 ms step first drops a resting body (g Δt)
    r.peak_speed = std::max(r.peak_speed, step.state.V_WCm.v.norm());
    r.peak_spin = std::max(r.peak_spin, step.state.V_WCm.w.norm());
  }
  if (!tap.steps.empty()) {
    const world::BodyState& end = tap.steps.back().state;
    r.end = end.p_WCm;
    r.yaw = Yaw(end.X_WB.q);
  }
  return r;
}

void WriteRun(const std::filesystem::path& dir, const std::string& slug, const Tap& tap) {
  Table f({"t", "force_N"});
  for (std::size_t i = 0; i < tap.t.size(); ++i)
    f.AddFormatted("{:.3f},{:.5f}", tap.t[i], tap.f[i]);
  WriteText(dir / (slug + "_force.csv"), f.Csv());
  Table b({"t", "x", "y", "z", "yaw_rad", "speed_mps", "spin_radps"});
  for (const Tap::Step& s : tap.steps) {
    const world::BodyState& st = s.state;
    b.AddFormatted("{:.3f},{:.6f},{:.6f},{:.6f},{:.5f},{:.5f},{:.5f}", s.t, st.p_WCm.x(),
                   st.p_WCm.y(), st.p_WCm.z(), Yaw(st.X_WB.q), st.V_WCm.v.norm(),
                   st.V_WCm.w.norm());
  }
  WriteText(dir / (slug + "_object.csv"), b.Csv());
}

std::string RunSlug(const Case& c, const Variant& v) {
  return c.Name() + "_" + Slug(v.label, '_');
}

std::vector<Case> Cases(const T37Options& options) {
  std::vector<Case> cases;
  for (const PointerKind& p : kPointers) {
    if (std::find(options.pointers.begin(), options.pointers.end(), p.name) ==
        options.pointers.end()) {
      continue;
    }
    for (const Shape& s : kShapes) {
      if (!options.shapes.empty() &&
          std::find(options.shapes.begin(), options.shapes.end(), s.name) == options.shapes.end()) {
        continue;
      }
      cases.push_back({&s, &p, 0.0});
      if (options.offcentre) cases.push_back({&s, &p, p.offset});
    }
  }
  return cases;
}

std::string PlotScript(const std::vector<Case>& cases) {
  std::string gp = fmt::format(
      "# t3.7: |f|, object x and y per case and method. gnuplot t3_7.gp\n"
      "set terminal pngcairo size 1500,{} enhanced font ',9'\nset output 't3_7.png'\n"
      "set datafile separator ','\nset grid\nset key top left\nset multiplot layout {},3\n",
      240 * cases.size(), cases.size());
  const auto panel = [&](const Case& c, const char* what, const char* file, int column) {
    gp += fmt::format("set title '{}: {}' noenhanced\nset xlabel 't (s)'\nplot ", c.Name(), what);
    for (std::size_t i = 0; i < std::size(kVariants); ++i) {
      gp += fmt::format("{}'runs/{}_{}.csv' using 1:{} with lines title '{}' noenhanced",
                        i ? ", " : "", RunSlug(c, kVariants[i]), file, column, kVariants[i].label);
    }
    gp += "\n";
  };
  for (const Case& c : cases) {
    panel(c, "|f| (N)", "force", 2);
    panel(c, "object x (m)", "object", 2);
    panel(c, "object y (m)", "object", 3);
  }
  return gp + "unset multiplot\n";
}

}  // namespace

T37Verdict Judge(const T37Result& r, const T37Result& ref) {
  T37Verdict v;
  // What the push allows, or where gravity adds speed (the ellipsoid), what the reference shows.
  v.speed_bound = kThrowBar * std::max(kSpeed, ref.peak_speed);
  v.thrown = r.peak_speed > v.speed_bound;
  if (r.rolling_radius > 0.0) {
    v.spin_bound = kThrowBar * std::max(kSpeed / r.rolling_radius, ref.peak_spin);
    v.spun = r.peak_spin > v.spin_bound;
  }
  if (r.coulomb_f > 0.0) {
    v.slide_error = r.mean_f / r.coulomb_f - 1.0;
    v.slide_ok = std::abs(*v.slide_error) <= kSlideBar;
  }
  // Off centre, a body that slides follows the reference: the push it took (the impulse ∫f dt
  // from the touch on, a vector: a push that turns the body off the pointer face ends early and
  // deflects it; the coupled tool's ringing averages out of it, not out of |f|), where it
  // went and which way it turned. A rolling body is kicked and rolls away freely: where it
  // stops is the kick's, not the push's, so it has only the speed and spin bars.
  if (r.offcentre && r.rolling_radius == 0.0) {
    const double ref_j = ref.impulse.norm();
    v.force_vs_ref = ref_j > 0.0 ? (r.impulse - ref.impulse).norm() / ref_j : 0.0;
    v.pose_error = (r.end.head<2>() - ref.end.head<2>()).norm();
    v.follows_ref = std::abs(*v.force_vs_ref) <= kForceBar && *v.pose_error <= kPoseBar;
    if (std::abs(ref.yaw) >= kTurnFloor) {
      v.same_turn = std::abs(r.yaw) >= kTurnFloor && (r.yaw > 0.0) == (ref.yaw > 0.0);
    }
  }
  return v;
}

std::vector<T37Result> RunT37Cases(const std::filesystem::path& out, bool quiet,
                                   const T37Options& options) {
  std::filesystem::create_directories(out / "runs");
  std::vector<T37Result> results;
  for (const Case& c : Cases(options)) {
    for (const Variant& v : kVariants) {
      if (!quiet) std::cout << "t3.7: " << c.Name() << " / " << v.label << "...\n";
      auto engine = session::MakeEngine(MakeSession(c, v));
      Tap tap;
      engine->Run(&tap);
      WriteRun(out / "runs", RunSlug(c, v), tap);
      results.push_back(Analyze(c, v, tap));
    }
  }
  return results;
}

int RunT37(const std::filesystem::path& out, bool quiet) {
  return RunT37(out, quiet, {});
}

int RunT37Full(const std::filesystem::path& out, bool quiet) {
  T37Options options;
  options.pointers = {"box", "sphere"};
  return RunT37(out, quiet, options);
}

int RunT37(const std::filesystem::path& out, bool quiet, const T37Options& options) {
  const std::vector<T37Result> results = RunT37Cases(out, quiet, options);
  const std::size_t per_case = std::size(kVariants);
  Table csv({"case", "method", "mean_force_N", "sd_force_N", "coulomb_force_N", "slide_error",
             "impulse_Ns", "impulse_vs_ref", "peak_speed_mps", "peak_spin_radps", "end_x_m",
             "end_y_m", "end_yaw_rad", "pose_error_m", "thrown", "spun", "follows_ref",
             "same_turn"});
  Table md({"case", "method", "mean |f| 2–5 s (N)", "sd (N)", "vs μmg", "∫f dt (x, y) (N·s)",
            "vs ref", "peak speed (m/s)", "peak spin (rad/s)", "end (x, y) (m)", "yaw (°)",
            "pos. error (m)", "verdict"});
  Checks checks;
  nlohmann::json summary;
  const auto cell = [](const std::optional<double>& x, const char* f) {
    return x ? fmt::format(fmt::runtime(f), *x) : std::string("—");
  };
  const auto flag = [](const std::optional<bool>& b) {
    return b ? (*b ? "1" : "0") : "";
  };
  for (std::size_t i = 0; i < results.size(); i += per_case) {
    const T37Result& ref = results[i];
    const std::string name =
        fmt::format("{}_{}_{}", ref.shape, ref.pointer, ref.offcentre ? "offcentre" : "centred");
    for (std::size_t k = 0; k < per_case; ++k) {
      const T37Result& r = results[i + k];
      const T37Verdict v = Judge(r, ref);
      std::string verdict;
      const auto note = [&](bool bad, const char* what) {
        if (bad) verdict += (verdict.empty() ? "" : ", ") + std::string(what);
      };
      note(v.thrown, "thrown");
      note(v.spun, "spun");
      note(v.slide_ok && !*v.slide_ok, "not μmg");
      note(v.follows_ref && !*v.follows_ref, "off ref");
      note(v.same_turn && !*v.same_turn, "turns the other way");
      csv.AddFormatted(
          "{},{},{:.4f},{:.4f},{:.4f},{},{:.4f},{},{:.4f},{:.3f},{:.4f},{:.4f},{:.4f},{},{},{},{},{"
          "}",
          name, r.method, r.mean_f, r.sd_f, r.coulomb_f, cell(v.slide_error, "{:.4f}"),
          r.impulse.norm(), cell(v.force_vs_ref, "{:.4f}"), r.peak_speed, r.peak_spin, r.end.x(),
          r.end.y(), r.yaw, cell(v.pose_error, "{:.4f}"), v.thrown ? 1 : 0, v.spun ? 1 : 0,
          flag(v.follows_ref), flag(v.same_turn));
      md.Add({name, r.method, fmt::format("{:.3f}", r.mean_f), fmt::format("{:.3f}", r.sd_f),
              v.slide_error ? fmt::format("{:+.1f} %", 100 * *v.slide_error) : "—",
              fmt::format("({:.2f}, {:.2f})", r.impulse.x(), r.impulse.y()),
              k > 0 && v.force_vs_ref ? fmt::format("{:.1f} %", 100 * *v.force_vs_ref) : "—",
              fmt::format("{:.3f}", r.peak_speed), fmt::format("{:.2f}", r.peak_spin),
              fmt::format("({:.3f}, {:.3f})", r.end.x(), r.end.y()),
              fmt::format("{:.0f}", r.yaw * 180.0 / std::numbers::pi),
              k > 0 ? cell(v.pose_error, "{:.4f}") : "—", verdict.empty() ? "ok" : verdict});
      summary["cases"][name][r.method] = {
          {"mean_force_N", r.mean_f},
          {"sd_force_N", r.sd_f},
          {"impulse_Ns", {r.impulse.x(), r.impulse.y(), r.impulse.z()}},
          {"peak_speed_mps", r.peak_speed},
          {"peak_spin_radps", r.peak_spin},
          {"end_m", {r.end.x(), r.end.y(), r.end.z()}},
          {"end_yaw_rad", r.yaw},
          {"thrown", v.thrown},
          {"spun", v.spun}};
      // The bars: nothing is thrown (every method); the proposed method and proxy-6dof
      // at 1 ms meet the analytic expectations, follow the reference off centre and turn its
      // way.
      if (k == 0) continue;
      checks.Add(fmt::format("{}_{}_not_thrown", name, r.method), !v.thrown, r.peak_speed,
                 v.speed_bound);
      if (r.method == std::string("proxy-6dof@20ms")) continue;
      if (r.rolling_radius > 0.0) {
        checks.Add(fmt::format("{}_{}_spin_within_2.5_v_over_r", name, r.method), !v.spun,
                   r.peak_spin, *v.spin_bound);
      }
      if (v.slide_ok) {
        checks.Add(fmt::format("{}_{}_coulomb_within_5pc", name, r.method), *v.slide_ok,
                   *v.slide_error, kSlideBar);
        // A steady slide feels steady: no more force fluctuation than the rigid tool's.
        checks.Add(fmt::format("{}_{}_force_sd_within_ref", name, r.method), r.sd_f <= ref.sd_f,
                   r.sd_f, ref.sd_f);
      }
      if (v.force_vs_ref) {
        checks.Add(fmt::format("{}_{}_impulse_within_10pc_of_ref", name, r.method),
                   std::abs(*v.force_vs_ref) <= kForceBar, *v.force_vs_ref, kForceBar);
      }
      if (v.pose_error) {
        checks.Add(fmt::format("{}_{}_position_within_2cm_of_ref", name, r.method),
                   *v.pose_error <= kPoseBar, *v.pose_error, kPoseBar);
      }
      if (v.same_turn) checks.Add(fmt::format("{}_{}_turns_as_ref", name, r.method), *v.same_turn);
    }
  }
  WriteText(out / "t3_7.csv", csv.Csv());
  WriteText(out / "t3_7.md", md.Markdown());
  Plot(out, "t3_7", PlotScript(Cases(options)), quiet);
  summary["experiment"] = "t3.7";
  summary["machine"] = MachineTag();
  summary["window_s"] = {kFrom, kDuration};
  summary["reference"] = kVariants[0].label;
  if (!quiet) std::cout << md.Markdown() << "\n";
  return FinishExperiment(out, std::move(summary), checks, quiet);
}

}  // namespace mrh::experiments::internal
