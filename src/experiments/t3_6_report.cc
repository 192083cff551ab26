// SPDX-License-Identifier: Apache-2.0
// Experiment t3.6's report: tables against the reference and Coulomb's force, the reference
// check under a 10 µm nudge, the acceptance bars as checks, and the plot.
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
#include "t3_6_impl.h"

namespace mrh::experiments::internal {
namespace {

using namespace t36;  // NOLINT(google-build-using-namespace): the experiment's own constants

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

// How far a nudged trio (a run and its two nudged twins) spreads: |f| and |τ| ranges (N, N·m),
// the largest position difference between two of them and the largest side offset (m).
struct Spread {
  double f_lo, f_hi, t_lo, t_hi, pose, side;
};

Spread SpreadOf(const Case& c, const T36Result* const member[3]) {
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
  return {f_lo, f_hi, t_lo, t_hi, pose, side};
}

// The reference check of one case: how much the reference and local-dynamics-6dof move when the
// pointer is nudged 10 µm sideways, in units of the acceptance bars (5 % of the reference's |f|,
// 10 % of its |τ|, 2 cm), and, where the case is mirror-symmetric (y -> -y), the share of the
// mean torque in τ_x and τ_z, which change sign under that mirror: the symmetric push defines
// none of it. Returns the figures as JSON; adds rows to `table`.
nlohmann::json CheckReference(const Case& c, const std::vector<T36Result>& runs, Table* table) {
  const T36Result& ref = runs[0];
  nlohmann::json out;
  for (int m = 0; m < 2; ++m) {
    const T36Result* member[3] = {&runs[kNudgedBase[m]], &runs[kNudged[m][0]],
                                  &runs[kNudged[m][1]]};
    const Spread spread = SpreadOf(c, member);
    const double f_lo = spread.f_lo, f_hi = spread.f_hi, t_lo = spread.t_lo, t_hi = spread.t_hi;
    const double pose = spread.pose, side = spread.side;
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
  return s.empty()
             ? s
             : "\nOpen (reported, not checked; docs/notes/local-dynamics-6dof.md): " + s + ".\n";
}

// The acceptance bars for one case. Every method: nothing thrown. local-dynamics-6dof at 20 ms and
// proxy-6dof at 1 ms: Coulomb's μ Σm g within 5 % where the boxes slide steadily; off centre,
// the reference's mean |f| within 10 %, its box positions within 2 cm and its turning direction.
// local-dynamics-6dof's result is a property of the push: a 10 µm nudge moves its force and box
// positions by less than one bar (not where the box tips over its edge: Case::tips).
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
  if (c.tips) return;
  const nlohmann::json& ld = rc[kVariants[kLocal20].label];
  for (const char* what : {"force", "position"}) {
    checks->Add(fmt::format("{}_local_dynamics_6dof_{}_within_a_bar_under_10um", c.name, what),
                ld[fmt::format("{}_spread_bars", what)].get<double>() <= 1.0);
  }
}

}  // namespace

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
