// SPDX-License-Identifier: Apache-2.0
// Experiment t3.6 (issue 14): a box pointer pushes, turns, tips and presses boxes on a floor
// (and, reported as open, pushes a box at its side edge);
// proxy-6dof at 1 ms (the thesis' 6-DOF reference), proxy-6dof at 20 ms, local-dynamics-6dof at
// 20 ms, all with the thesis torque model (eq. 3.8). That reference is not a contact wrench
// (docs/theory.md): t3.7 judges the default contact model against a rigid tool and mechanics.
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
  bool open = false;  // a known failure (docs/architecture.md): reported, not checked
};

// The box reaches the wall at 2.5 s; the pointer stops 8 mm further (about 16 N of press).

constexpr Case kCases[] = {{"face", "t3_6_push.xml", 0.0, 0.05, kDuration, true, 0.5},
                           {"offcentre", "t3_6_push.xml", 0.03, 0.05, kDuration, false, 0.0},
                           {"tip", "t3_6_tip.xml", 0.0, 0.085, kDuration, true, 0.0},
                           {"wall", "t3_6_wall.xml", 0.0, 0.05, 2.6, true, 0.0},
                           {"row", "t3_6_row.xml", 0.0, 0.05, kDuration, true, 0.5},
                           // The pointer centred on the box's side edge, half its face overhanging:
                           // local-dynamics-6dof flings the box (open, see docs/architecture.md).
                           {"edge", "t3_6_push.xml", 0.05, 0.05, kDuration, false, 0.0, true}};

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
    {"proxy-6dof@1ms", "proxy-6dof", 0.001, 0.0},
    {"proxy-6dof@20ms", "proxy-6dof", 0.02, 0.0},
    {"local-dynamics-6dof@20ms", "local-dynamics-6dof", 0.02, 0.0},
    {"proxy-6dof@1ms y-10um", "proxy-6dof", 0.001, -kNudge},
    {"proxy-6dof@1ms y+10um", "proxy-6dof", 0.001, kNudge},
    {"local-dynamics-6dof@20ms y-10um", "local-dynamics-6dof", 0.02, -kNudge},
    {"local-dynamics-6dof@20ms y+10um", "local-dynamics-6dof", 0.02, kNudge}};
constexpr std::size_t kCompared = 3;  // the three methods; the rest are the check's
// kVariants' indices of a method's nudged runs (reference first, then local-dynamics-6dof).
constexpr std::size_t kNudged[2][2] = {{3, 4}, {5, 6}};

session::Session MakeSession(const Case& c, const Variant& v) {
  nlohmann::json j;
  j["scene"] = c.scene;
  j["method"] = v.method;
  j["physics_dt"] = v.physics_dt;
  j["haptic_dt"] = 0.001;
  j["duration"] = kDuration;
  j["rendering"] = {{"stiffness", 2000.0}, {"damping", 5.0},  {"rot_stiffness", 20.0},
                    {"rot_damping", 0.1},  {"friction", 0.3}, {"torque_model", "thesis"}};
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
    Step s{step.t, {}, 0.0, 0.0, 0.0};
    for (const int b : boxes) {
      const world::BodyState st = world.body_state(b);
      s.p.push_back(st.p_WCm);
      s.spin = std::max(s.spin, st.V_WCm.w.norm());
      s.speed = std::max(s.speed, st.V_WCm.v.norm());
    }
    const Quat q = world.body_state(boxes[0]).X_WB.q;
    s.angle = 2.0 * std::acos(std::min(1.0, std::abs(q.w())));
    steps.push_back(std::move(s));
  }

  struct Step {
    double t;
    std::vector<Vec3> p;
    double spin, angle, speed;
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
    if (s.t <= kPoseAt + 1e-9) r.pose_at = s.p;
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
             "peak_speed_mps", "force_vs_coulomb"}};
  Table md{{"case", "method", "mean |f| (N)", "vs ref", "vs μΣmg", "sd f (N)", "sd ratio",
            "mean |τ| (N·m)", "vs ref", "pos. error at 4 s (m)", "peak spin (rad/s)",
            "peak speed (m/s)"}};
};

// One row; returns the bars for local-dynamics-6dof as a JSON object.
nlohmann::json Compare(const Case& c, const Variant& v, const T36Result& r, const T36Result& ref,
                       Tables* tables) {
  const double df = r.mean_f / ref.mean_f - 1.0;
  const double dtau = ref.mean_tau > 0.0 ? r.mean_tau / ref.mean_tau - 1.0 : 0.0;
  const double sd_ratio = ref.sd_f > 0.0 ? r.sd_f / ref.sd_f : 0.0;
  const double err = PoseError(r, ref);
  // Against the analytic sliding force where the case has one (NaN in the CSV otherwise).
  const double dc = r.sliding_f > 0.0 ? r.mean_f / r.sliding_f - 1.0 : std::nan("");
  tables->csv.AddFormatted(
      "{},{},{:.4f},{:.4f},{:.4f},{:.3f},{:.4f},{:.4f},{:.4f},{:.3f},{:.4f},{:.4f}", c.name,
      v.label, r.mean_f, df, r.sd_f, sd_ratio, r.mean_tau, dtau, err, r.peak_spin, r.peak_speed,
      dc);
  tables->md.Add(
      {c.name, v.label, fmt::format("{:.3f}", r.mean_f), fmt::format("{:+.1f} %", 100 * df),
       r.sliding_f > 0.0 ? fmt::format("{:+.1f} %", 100 * dc) : "—", fmt::format("{:.3f}", r.sd_f),
       fmt::format("{:.2f}", sd_ratio), fmt::format("{:.3f}", r.mean_tau),
       fmt::format("{:+.1f} %", 100 * dtau), fmt::format("{:.4f}", err),
       fmt::format("{:.2f}", r.peak_spin), fmt::format("{:.3f}", r.peak_speed)});
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
          {"bars",
           {{"force", std::abs(df) <= 0.05},
            {"torque", std::abs(dtau) <= 0.10},
            {"sd", r.sd_f <= 2.0 * ref.sd_f},
            {"position", err <= 0.02},
            {"spin", r.peak_spin <= ref.peak_spin + 1.0},
            {"no_fling", r.peak_speed < 2.0 * ref.peak_speed}}}};
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
    const T36Result* member[3] = {&runs[m == 0 ? 0 : 2], &runs[kNudged[m][0]],
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
    const char* label = kVariants[m == 0 ? 0 : 2].label;
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
  return s.empty() ? s
                   : "\nOpen (reported, not checked; docs/architecture.md): " + s +
                         ". local-dynamics-6dof flings the box there.\n";
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
    // local-dynamics-6dof's result is a property of the push: a 10 µm nudge moves it by less
    // than one bar, and in a mirror-symmetric case most of its torque is the mirror-even part.
    if (c.open) continue;
    // Where the boxes slide steadily, local-dynamics-6dof's mean |f| is Coulomb's μ Σm |g|
    // within the 5 % force bar.
    const T36Result& ld20 = results[ci][2];
    if (ld20.sliding_f > 0.0) {
      checks.Add(fmt::format("{}_local_dynamics_6dof_force_within_5pc_of_coulomb", c.name),
                 std::abs(ld20.mean_f / ld20.sliding_f - 1.0) <= 0.05,
                 ld20.mean_f / ld20.sliding_f - 1.0, 0.05);
    }
    const nlohmann::json& ld = rc["local-dynamics-6dof@20ms"];
    for (const char* what : {"force", "torque", "position"}) {
      checks.Add(fmt::format("{}_local_dynamics_6dof_{}_within_a_bar_under_10um", c.name, what),
                 ld[fmt::format("{}_spread_bars", what)].get<double>() <= 1.0);
    }
    if (c.mirror) {
      checks.Add(fmt::format("{}_local_dynamics_6dof_torque_mostly_mirror_even", c.name),
                 ld["mirror_odd_torque_share"].get<double>() < 0.5);
    }
  }
  // The essential result: on the face push, local-dynamics-6dof at 20 ms meets the force, spread,
  // position and spin bars against the 1 ms reference (the torque bar is reported, not checked).
  const nlohmann::json& face = summary["cases"]["face"]["local-dynamics-6dof@20ms"]["bars"];
  for (const char* bar : {"force", "sd", "position", "spin"}) {
    checks.Add(fmt::format("face_local_dynamics_6dof_{}", bar), face[bar].get<bool>());
  }
  // And proxy-6dof at 20 ms flings nothing in any case (peak speed below 2x the reference's).
  for (const Case& c : kCases) {
    checks.Add(fmt::format("{}_proxy_6dof_20ms_no_fling", c.name),
               summary["cases"][c.name]["proxy-6dof@20ms"]["bars"]["no_fling"].get<bool>());
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
