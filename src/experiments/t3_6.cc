// SPDX-License-Identifier: Apache-2.0
// Experiment t3.6: a box pointer pushes, turns, tips and presses boxes on a floor (and, reported
// as open, pushes a box at its side edge); proxy-6dof at 1 and 20 ms and local-dynamics-6dof at
// 20 ms with the contact torque model, against a consistent reference — the tool as a rigid
// MuJoCo body at 1 ms (virtual coupling with the rendering's gains and the scene's tool–box
// friction) — and against mechanics: Coulomb's μ Σm g where the boxes slide steadily.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <vector>

#include "experiment_table.h"
#include "experiment_util.h"
#include "experiments_impl.h"
#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::experiments::internal {
namespace {

constexpr double kSpeed = 0.08;    // m/s along +x (scenes/t3_6_push.json)
constexpr double kX0 = -0.16;      // m, pointer at t = 0; it touches the box at 1.25 s
constexpr double kDuration = 5.0;  // s
constexpr double kFrom = 2.0;      // s, statistics window 2–5 s
// Peak speed counts from here: after the boxes settled on the floor (a 20 ms step drops them at
// g Δt = 0.2 m/s), before the touch.
constexpr double kSpeedFrom = 1.0;  // s
constexpr double kPoseAt = 4.0;     // s, the "box positions within 2 cm after 4 s"

struct Case {
  const char* name;
  const char* scene;
  double y, z;        // pointer offset (m)
  double push_until;  // s; the pointer holds still afterwards
  bool mirror;        // the scene and the push are symmetric under y -> -y
  // The boxes slide steadily over the window: the push is Coulomb's μ Σm |g| with this floor
  // friction (the scene's geom default; 0: not a steady slide).
  double slide_mu;
  double tool_mu;     // the scene's box friction: MuJoCo's tool–box contact takes it (max rule)
  bool open = false;  // a known failure (docs/architecture.md): reported, not checked
};

// The box reaches the wall at 2.5 s; the pointer stops 8 mm further (about 16 N of press).

constexpr Case kCases[] = {{"face", "t3_6_push.xml", 0.0, 0.05, kDuration, true, 0.5, 0.5},
                           {"offcentre", "t3_6_push.xml", 0.03, 0.05, kDuration, false, 0.0, 0.5},
                           {"tip", "t3_6_tip.xml", 0.0, 0.085, kDuration, true, 0.0, 1.0},
                           {"wall", "t3_6_wall.xml", 0.0, 0.05, 2.6, true, 0.0, 0.5},
                           {"row", "t3_6_row.xml", 0.0, 0.05, kDuration, true, 0.5, 0.5},
                           // The pointer centred on the box's side edge, half its face overhanging.
                           {"edge", "t3_6_push.xml", 0.05, 0.05, kDuration, false, 0.0, 0.5, true}};

struct Variant {
  const char* label;
  const char* method;
  double physics_dt;
  double dy;  // m, extra pointer offset along y (the sensitivity runs)
};

// The reference check: the reference and local-dynamics-6dof again with the pointer 10 µm to
// either side, a fifth of a Novint Falcon's resolution and far below what a hand can place. A
// result that changes more than the bar under that offset is not a property of the push.
constexpr double kNudge = 1e-5;  // m

constexpr Variant kVariants[] = {
    {"virtual-coupling@1ms", "virtual-coupling", 0.001, 0.0},
    {"proxy-6dof@1ms", "proxy-6dof", 0.001, 0.0},
    {"proxy-6dof@20ms", "proxy-6dof", 0.02, 0.0},
    {"local-dynamics-6dof@20ms", "local-dynamics-6dof", 0.02, 0.0},
    {"virtual-coupling@1ms y-10um", "virtual-coupling", 0.001, -kNudge},
    {"virtual-coupling@1ms y+10um", "virtual-coupling", 0.001, kNudge},
    {"local-dynamics-6dof@20ms y-10um", "local-dynamics-6dof", 0.02, -kNudge},
    {"local-dynamics-6dof@20ms y+10um", "local-dynamics-6dof", 0.02, kNudge}};
constexpr std::size_t kCompared = 4;  // the reference and the three methods; the rest: the check
constexpr std::size_t kProxy1 = 1, kProxy20 = 2, kLocal20 = 3;
// kVariants' indices of a method's nudged runs (reference first, then local-dynamics-6dof).
constexpr std::size_t kNudged[2][2] = {{4, 5}, {6, 7}};
constexpr std::size_t kNudgedBase[2] = {0, kLocal20};

// Rendering gains shared by every method; the virtual coupling's are matched to them. Its tool
// (0.1 kg, 1e-3 kg·m²: the pointer weighs 48 g) is as heavy as keeps the coupling stable.
constexpr double kStiffness = 2000.0;   // N/m
constexpr double kDamping = 5.0;        // N·s/m
constexpr double kRotStiffness = 20.0;  // N·m/rad
constexpr double kToolMass = 0.1;       // kg
constexpr double kToolInertia = 0.001;  // kg·m², each principal moment
constexpr double kThrowBar = 2.5;       // peak speed ≤ 2.5 × max(push, reference's peak)
constexpr double kSlideBar = 0.05;      // steady slide: mean |f| within 5 % of μ Σm g
constexpr double kForceBar = 0.10;      // off centre: mean |f| within 10 % of the reference's
constexpr double kPoseBar = 0.02;       // m: box positions within 2 cm of the reference's
// A turn smaller than this in the reference has no direction worth comparing.
constexpr double kTurnFloor = 5.0 * std::numbers::pi / 180.0;

session::Session MakeSession(const Case& c, const Variant& v) {
  nlohmann::json j;
  j["scene"] = c.scene;
  j["method"] = v.method;
  j["physics_dt"] = v.physics_dt;
  j["haptic_dt"] = 0.001;
  j["duration"] = kDuration;
  j["rendering"] = {{"stiffness", kStiffness},
                    {"damping", kDamping},
                    {"rot_stiffness", kRotStiffness},
                    {"friction", c.tool_mu},
                    {"torque_model", "contact"},
                    {"coupling_stiffness", kStiffness},
                    {"coupling_damping", kDamping},
                    {"coupling_rot_stiffness", kRotStiffness},
                    {"tool_mass", kToolMass},
                    {"tool_inertia", {kToolInertia, kToolInertia, kToolInertia}}};
  j["safety"] = {{"ramp", false}};
  const double x_end = kX0 + kSpeed * c.push_until;
  const double y = c.y + v.dy;
  nlohmann::json frames = {{0.0, kX0, y, c.z, 1, 0, 0, 0},
                           {c.push_until, x_end, y, c.z, 1, 0, 0, 0}};
  if (c.push_until < kDuration) frames.push_back({kDuration, x_end, y, c.z, 1, 0, 0, 0});
  j["device"] = {{"type", "scripted"}, {"keyframes", frames}};
  return session::ParseSession(j.dump(), ScenesDir(), {},
                               fmt::format("t3.6 {} ({})", c.name, v.label));
}

// Rendered |f|, |τ| per tick; the first box's x and tilt angle and every box's COM per step.
struct Tap final : engine::Recorder {
  void OnTick(const engine::TickRecord& tick) override {
    t.push_back(tick.t);
    f.push_back(tick.rendered_W.f.norm());
    tau.push_back(tick.rendered_W.tau.norm());
    tau_W.push_back(tick.rendered_W.tau);
  }

  void OnStep(const engine::StepRecord& step, const world::World& world) override {
    if (boxes.empty()) {
      for (const char* name : {"box", "box2"}) {
        const int b = world.FindBody(name);
        if (b >= 0) {
          boxes.push_back(b);
          mass += world.body(b).mass;
        }
      }
      g = world.gravity().norm();
    }
    Step s{step.t, {}, 0.0, 0.0, 0.0, 0.0};
    for (const int b : boxes) {
      const world::BodyState st = world.body_state(b);
      s.p.push_back(st.p_WCm);
      s.spin = std::max(s.spin, st.V_WCm.w.norm());
      s.speed = std::max(s.speed, st.V_WCm.v.norm());
    }
    const Quat q = world.body_state(boxes[0]).X_WB.q;
    s.angle = 2.0 * std::acos(std::min(1.0, std::abs(q.w())));
    const Vec3 x_W = q * Vec3::UnitX();
    s.yaw = std::atan2(x_W.y(), x_W.x());
    steps.push_back(std::move(s));
  }

  struct Step {
    double t;
    std::vector<Vec3> p;
    double spin, angle, speed, yaw;
  };

  std::vector<int> boxes;
  double mass = 0.0, g = 0.0;  // kg, the boxes' total; m/s²
  std::vector<double> t, f, tau;
  std::vector<Vec3> tau_W;
  std::vector<Step> steps;
};

void MeanSd(const std::vector<double>& t, const std::vector<double>& x, double* mean, double* sd) {
  double s = 0.0, s2 = 0.0, n = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < kFrom) continue;
    s += x[i];
    s2 += x[i] * x[i];
    n += 1.0;
  }
  *mean = n > 0 ? s / n : 0.0;
  *sd = n > 0 ? std::sqrt(std::max(0.0, s2 / n - *mean * *mean)) : 0.0;
}

T36Result Analyze(const Case& c, const Tap& tap) {
  T36Result r;
  r.sliding_f = c.slide_mu * tap.mass * tap.g;
  MeanSd(tap.t, tap.f, &r.mean_f, &r.sd_f);
  MeanSd(tap.t, tap.tau, &r.mean_tau, &r.sd_tau);
  double n = 0.0;
  for (std::size_t i = 0; i < tap.t.size(); ++i) {
    if (tap.t[i] < kFrom) continue;
    r.mean_tau_W += tap.tau_W[i];
    n += 1.0;
  }
  if (n > 0.0) r.mean_tau_W /= n;
  for (const Tap::Step& s : tap.steps) {
    r.peak_spin = std::max(r.peak_spin, s.spin);
    if (s.t >= kSpeedFrom) r.peak_speed = std::max(r.peak_speed, s.speed);
    if (s.t <= kPoseAt + 1e-9) {
      r.pose_at = s.p;
      r.yaw_at = s.yaw;
    }
  }
  return r;
}

void WriteRun(const std::filesystem::path& dir, const std::string& slug, const Tap& tap) {
  Table f({"t", "force_N", "torque_Nm"});
  for (std::size_t i = 0; i < tap.t.size(); ++i) {
    f.AddFormatted("{:.3f},{:.5f},{:.5f}", tap.t[i], tap.f[i], tap.tau[i]);
  }
  WriteText(dir / (slug + "_wrench.csv"), f.Csv());
  // The first box's pose, the boxes' peak spin and speed; a second box's (row) position.
  Table b({"t", "x", "y", "z", "tilt_rad", "spin_radps", "speed_mps", "x2", "y2", "z2"});
  for (const Tap::Step& s : tap.steps) {
    const Vec3 p2 = s.p.size() > 1 ? s.p[1] : Vec3::Constant(std::nan(""));
    b.AddFormatted("{:.3f},{:.6f},{:.6f},{:.6f},{:.6f},{:.5f},{:.5f},{:.6f},{:.6f},{:.6f}", s.t,
                   s.p[0].x(), s.p[0].y(), s.p[0].z(), s.angle, s.spin, s.speed, p2.x(), p2.y(),
                   p2.z());
  }
  WriteText(dir / (slug + "_box.csv"), b.Csv());
}

std::string RunSlug(const Case& c, const Variant& v) {
  return std::string(c.name) + "_" + Slug(v.label, '_');
}

std::string PlotScript() {
  std::string gp = fmt::format(
      "# t3.6: |f|, |tau|, box x and tilt per case and method. gnuplot t3_6.gp\n"
      "set terminal pngcairo size 1800,{} enhanced font ',9'\nset output 't3_6.png'\n"
      "set datafile separator ','\nset grid\nset key top left\nset multiplot layout {},4\n",
      300 * std::size(kCases), std::size(kCases));
  const auto panel = [&](const Case& c, const char* what, const char* file, int column) {
    gp += fmt::format("set title '{}: {}'\nset xlabel 't (s)'\nplot ", c.name, what);
    for (std::size_t i = 0; i < kCompared; ++i) {
      gp += fmt::format("{}'runs/{}_{}.csv' using 1:{} with lines title '{}' noenhanced",
                        i ? ", " : "", RunSlug(c, kVariants[i]), file, column, kVariants[i].label);
    }
    gp += "\n";
  };
  for (const Case& c : kCases) {
    panel(c, "|f| (N)", "wrench", 2);
    panel(c, "|tau| (N m)", "wrench", 3);
    panel(c, "box x (m)", "box", 2);
    panel(c, "box tilt (rad)", "box", 5);
  }
  return gp + "unset multiplot\n";
}

double PoseError(const T36Result& r, const T36Result& ref) {
  double e = 0.0;
  for (std::size_t i = 0; i < r.pose_at.size() && i < ref.pose_at.size(); ++i) {
    e = std::max(e, (r.pose_at[i] - ref.pose_at[i]).norm());
  }
  return e;
}

struct Tables {
  Table csv{{"case", "method", "mean_force_N", "force_vs_ref", "sd_force_N", "sd_ratio",
             "mean_torque_Nm", "torque_vs_ref", "position_error_m", "peak_spin_radps",
             "peak_speed_mps", "force_vs_coulomb", "yaw_at_4s_rad"}};
  Table md{{"case", "method", "mean |f| (N)", "vs ref", "vs μΣmg", "sd f (N)", "sd ratio",
            "mean |τ| (N·m)", "vs ref", "pos. error at 4 s (m)", "peak spin (rad/s)",
            "peak speed (m/s)", "yaw at 4 s (°)"}};
};

// Whether r turns the first box the reference's way, by kTurnFloor at least (nullopt: the
// reference turns it less, no direction to compare).
std::optional<bool> SameTurn(const T36Result& r, const T36Result& ref) {
  if (std::abs(ref.yaw_at) < kTurnFloor) return std::nullopt;
  return std::abs(r.yaw_at) >= kTurnFloor && (r.yaw_at > 0.0) == (ref.yaw_at > 0.0);
}

// One row; returns its figures and bars against the reference as a JSON object.
nlohmann::json Compare(const Case& c, const Variant& v, const T36Result& r, const T36Result& ref,
                       Tables* tables) {
  const double df = r.mean_f / ref.mean_f - 1.0;
  const double dtau = ref.mean_tau > 0.0 ? r.mean_tau / ref.mean_tau - 1.0 : 0.0;
  const double sd_ratio = ref.sd_f > 0.0 ? r.sd_f / ref.sd_f : 0.0;
  const double err = PoseError(r, ref);
  // Against the analytic sliding force where the case has one (NaN in the CSV otherwise).
  const double dc = r.sliding_f > 0.0 ? r.mean_f / r.sliding_f - 1.0 : std::nan("");
  tables->csv.AddFormatted(
      "{},{},{:.4f},{:.4f},{:.4f},{:.3f},{:.4f},{:.4f},{:.4f},{:.3f},{:.4f},{:.4f},{:.4f}", c.name,
      v.label, r.mean_f, df, r.sd_f, sd_ratio, r.mean_tau, dtau, err, r.peak_spin, r.peak_speed, dc,
      r.yaw_at);
  tables->md.Add(
      {c.name, v.label, fmt::format("{:.3f}", r.mean_f), fmt::format("{:+.1f} %", 100 * df),
       r.sliding_f > 0.0 ? fmt::format("{:+.1f} %", 100 * dc) : "—", fmt::format("{:.3f}", r.sd_f),
       fmt::format("{:.2f}", sd_ratio), fmt::format("{:.3f}", r.mean_tau),
       fmt::format("{:+.1f} %", 100 * dtau), fmt::format("{:.4f}", err),
       fmt::format("{:.2f}", r.peak_spin), fmt::format("{:.3f}", r.peak_speed),
       fmt::format("{:.0f}", r.yaw_at * 180.0 / std::numbers::pi)});
  const std::optional<bool> turn = SameTurn(r, ref);
  return {{"mean_force_N", r.mean_f},
          {"force_vs_ref", df},
          {"sd_force_N", r.sd_f},
          {"sd_ratio", sd_ratio},
          {"mean_torque_Nm", r.mean_tau},
          {"torque_vs_ref", dtau},
          {"position_error_m", err},
          {"peak_spin_radps", r.peak_spin},
          {"peak_speed_mps", r.peak_speed},
          {"coulomb_force_N", r.sliding_f},
          {"force_vs_coulomb", r.sliding_f > 0.0 ? nlohmann::json(dc) : nlohmann::json()},
          {"yaw_at_4s_rad", r.yaw_at},
          {"bars",
           {{"coulomb",
             r.sliding_f > 0.0 ? nlohmann::json(std::abs(dc) <= kSlideBar) : nlohmann::json()},
            {"force", std::abs(df) <= kForceBar},
            {"position", err <= kPoseBar},
            {"same_turn", turn ? nlohmann::json(*turn) : nlohmann::json()},
            {"not_thrown", r.peak_speed <= kThrowBar * std::max(kSpeed, ref.peak_speed)}}}};
}

// The reference check of one case: how much the reference and local-dynamics-6dof move when the
// pointer is nudged 10 µm sideways, in units of the bars (5 % of the reference's |f|,
// 10 % of its |τ|, 2 cm), and, where the case is mirror-symmetric (y -> -y), the share of the
// mean torque in τ_x and τ_z, which change sign under that mirror: the symmetric push defines
// none of it. Returns the figures as JSON; adds rows to `table`.
nlohmann::json CheckReference(const Case& c, const std::vector<T36Result>& runs, Table* table) {
  const T36Result& ref = runs[0];
  nlohmann::json out;
  for (int m = 0; m < 2; ++m) {
    const T36Result* member[3] = {&runs[kNudgedBase[m]], &runs[kNudged[m][0]],
                                  &runs[kNudged[m][1]]};
    double f_lo = member[0]->mean_f, f_hi = f_lo, t_lo = member[0]->mean_tau, t_hi = t_lo;
    double pose = 0.0, side = 0.0;
    for (int i = 0; i < 3; ++i) {
      f_lo = std::min(f_lo, member[i]->mean_f);
      f_hi = std::max(f_hi, member[i]->mean_f);
      t_lo = std::min(t_lo, member[i]->mean_tau);
      t_hi = std::max(t_hi, member[i]->mean_tau);
      for (int j = 0; j < i; ++j) pose = std::max(pose, PoseError(*member[i], *member[j]));
      for (const Vec3& p : member[i]->pose_at) side = std::max(side, std::abs(p.y() - c.y));
    }
    const double f_bars = (f_hi - f_lo) / (0.05 * ref.mean_f);
    const double t_bars = ref.mean_tau > 0.0 ? (t_hi - t_lo) / (0.10 * ref.mean_tau) : 0.0;
    const double pose_bars = pose / 0.02;
    const Vec3& tau = member[0]->mean_tau_W;
    const double odd =
        member[0]->mean_tau > 0.0 ? std::hypot(tau.x(), tau.z()) / member[0]->mean_tau : 0.0;
    const char* label = kVariants[kNudgedBase[m]].label;
    table->Add({c.name, label, fmt::format("{:.3f}–{:.3f}", f_lo, f_hi),
                fmt::format("{:.2f}", f_bars), fmt::format("{:.3f}–{:.3f}", t_lo, t_hi),
                fmt::format("{:.2f}", t_bars), fmt::format("{:.4f}", pose),
                fmt::format("{:.2f}", pose_bars),
                fmt::format("{:+.3f} / {:+.3f} / {:+.3f}", member[1]->mean_tau_W.x(), tau.x(),
                            member[2]->mean_tau_W.x()),
                c.mirror ? fmt::format("{:.2f}", odd) : "—",
                c.mirror ? fmt::format("{:.4f}", side) : "—"});
    out[label] = {{"force_range_N", {f_lo, f_hi}},
                  {"force_spread_bars", f_bars},
                  {"torque_range_Nm", {t_lo, t_hi}},
                  {"torque_spread_bars", t_bars},
                  {"position_spread_m", pose},
                  {"position_spread_bars", pose_bars},
                  {"tau_x_Nm", {member[1]->mean_tau_W.x(), tau.x(), member[2]->mean_tau_W.x()}}};
    if (c.mirror) {
      out[label]["mirror_odd_torque_share"] = odd;
      out[label]["max_side_offset_m"] = side;
    }
  }
  return out;
}

// The cases reported but not checked, as a markdown paragraph (empty if none).
std::string OpenCases() {
  std::string s;
  for (const Case& c : kCases) {
    if (c.open) s += fmt::format("{}{}", s.empty() ? "" : ", ", c.name);
  }
  return s.empty() ? s : "\nOpen (reported, not checked; docs/architecture.md): " + s + ".\n";
}

// The bars for one case. Every method: nothing thrown. local-dynamics-6dof at 20 ms and
// proxy-6dof at 1 ms: Coulomb's μ Σm g within 5 % where the boxes slide steadily; off centre,
// the reference's mean |f| within 10 %, its box positions within 2 cm and its turning direction.
// local-dynamics-6dof's result is a property of the push: a 10 µm nudge moves its force and box
// positions by less than one bar.
void AddChecks(const Case& c, const nlohmann::json& rows, const nlohmann::json& rc,
               Checks* checks) {
  if (c.open) return;
  for (std::size_t vi = 1; vi < kCompared; ++vi) {
    const std::string m = Slug(kVariants[vi].label, '_');
    const nlohmann::json& row = rows[kVariants[vi].label];
    const nlohmann::json& bars = row["bars"];
    checks->Add(fmt::format("{}_{}_not_thrown", c.name, m), bars["not_thrown"].get<bool>());
    if (vi == kProxy20) continue;
    if (!bars["coulomb"].is_null()) {
      checks->Add(fmt::format("{}_{}_coulomb_within_5pc", c.name, m), bars["coulomb"].get<bool>(),
                  row["force_vs_coulomb"].get<double>(), kSlideBar);
    }
    if (c.y == 0.0) continue;  // the off-centre push
    checks->Add(fmt::format("{}_{}_force_within_10pc_of_ref", c.name, m), bars["force"].get<bool>(),
                row["force_vs_ref"].get<double>(), kForceBar);
    checks->Add(fmt::format("{}_{}_position_within_2cm_of_ref", c.name, m),
                bars["position"].get<bool>(), row["position_error_m"].get<double>(), kPoseBar);
    if (!bars["same_turn"].is_null()) {
      checks->Add(fmt::format("{}_{}_turns_as_ref", c.name, m), bars["same_turn"].get<bool>());
    }
  }
  const nlohmann::json& ld = rc[kVariants[kLocal20].label];
  for (const char* what : {"force", "position"}) {
    checks->Add(fmt::format("{}_local_dynamics_6dof_{}_within_a_bar_under_10um", c.name, what),
                ld[fmt::format("{}_spread_bars", what)].get<double>() <= 1.0);
  }
}

}  // namespace

std::vector<std::vector<T36Result>> RunT36Cases(const std::filesystem::path& out, bool quiet) {
  std::filesystem::create_directories(out / "runs");
  std::vector<std::vector<T36Result>> results;
  for (const Case& c : kCases) {
    results.emplace_back();
    for (const Variant& v : kVariants) {
      if (!quiet) std::cout << "t3.6: " << c.name << " / " << v.label << "...\n";
      auto engine = session::MakeEngine(MakeSession(c, v));
      Tap tap;
      engine->Run(&tap);
      WriteRun(out / "runs", RunSlug(c, v), tap);
      T36Result r = Analyze(c, tap);
      r.case_name = c.name;
      r.method = v.label;
      results.back().push_back(std::move(r));
    }
  }
  return results;
}

int RunT36(const std::filesystem::path& out, bool quiet) {
  const auto results = RunT36Cases(out, quiet);
  nlohmann::json summary;
  Tables tables;
  Checks checks;
  Table check({"case", "method", "mean |f| at y ±10 µm (N)", "spread (bars)",
               "mean |τ| at y ±10 µm (N·m)", "spread (bars)", "pos. spread at 4 s (m)",
               "spread (bars)", "mean τ_x at −10 / 0 / +10 µm (N·m)", "mirror-odd share of τ",
               "max |y| at 4 s (m)"});
  for (std::size_t ci = 0; ci < std::size(kCases); ++ci) {
    const Case& c = kCases[ci];
    for (std::size_t vi = 0; vi < kCompared; ++vi) {
      summary["cases"][c.name][kVariants[vi].label] =
          Compare(c, kVariants[vi], results[ci][vi], results[ci][0], &tables);
    }
    const nlohmann::json rc = CheckReference(c, results[ci], &check);
    summary["reference_check"][c.name] = rc;
    AddChecks(c, summary["cases"][c.name], rc, &checks);
  }
  WriteText(out / "t3_6.csv", tables.csv.Csv());
  WriteText(out / "t3_6.md",
            tables.md.Markdown() + OpenCases() +
                "\nReference check (pointer nudged 10 µm in y; "
                "a bar is 5 % of the reference's |f|, 10 % of its |τ|, 2 cm):\n\n" +
                check.Markdown());
  WriteText(out / "t3_6_reference_check.csv", check.Csv());
  Plot(out, "t3_6", PlotScript(), quiet);
  summary["experiment"] = "t3.6";
  summary["machine"] = MachineTag();
  summary["window_s"] = {kFrom, kDuration};
  if (!quiet) std::cout << tables.md.Markdown() << "\n" << check.Markdown();
  return FinishExperiment(out, std::move(summary), checks, quiet);
}

}  // namespace mrh::experiments::internal
