// SPDX-License-Identifier: Apache-2.0
// Experiment T3.5 (thesis §3.4.1, fig. 3.18): the rotation weight R_w swept on the T3.1 motion.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "experiment_table.h"
#include "experiment_util.h"
#include "experiments_impl.h"
#include "mrh/session/session.h"

namespace mrh::experiments::internal {
namespace {

// The T3.1 cube and motion (scenes/t3_1.xml, t3_1_trajectory.csv): half side, edge depth, the
// roll and the edge → face transition (s).
constexpr double kHalf = 0.1;
constexpr double kEdgeDepth = 3.0 / 9000.0;
constexpr double kRoll[] = {1.5, 3.8};
constexpr double kTransition[] = {3.6, 4.2};
// A constrained IR point is a cube vertex when it lies this close to it (vertices are 0.2 m
// apart; region vertices carry qhull's rounding, ~1e-12 m).
constexpr double kSameVertex = 1e-6;

struct SweepPoint {
  double multiplier = 0.0;
  double R_w = 0.0;               // m², isotropic for the cube
  double free_penetration = 0.0;  // m, deepest unconstrained vertex at the proxy pose
  double free_penetration_time = 0.0;
  double bound_penetration = 0.0;     // m, deepest constrained vertex at the proxy (≈ 0)
  double peak_torque = 0.0;           // N·m, max |τ| while rolling
  double peak_torque_analytic = 0.0;  // single edge at the flat limit, k_r δ h/(R_w + h²)
  double edge_torque_error = 0.0;   // N·m, max |τ − τ_analytic| over converged one-edge ticks
  double edge_peak_torque = 0.0;    // N·m, max |τ| over those ticks
  double edge_peak_analytic = 0.0;  // N·m, the analytic τ of that tick (its own δ and lever)
  int edge_ticks = 0;
  double mean_torque = 0.0;  // N·m, mean |τ| while rolling
  double max_torque = 0.0;   // N·m, max |τ| over the run
  double force_jump = 0.0;   // N, max tick-to-tick |Δf| in the transition
  double torque_jump = 0.0;  // N·m, max tick-to-tick |Δτ| in the transition
  double mean_sweeps = 0.0;
  int unconverged = 0;
};

bool In(double t, const double (&range)[2]) {
  return t >= range[0] && t < range[1];
}

Vec3 Vertex(int i) {
  return Vec3(i & 1 ? kHalf : -kHalf, i & 2 ? kHalf : -kHalf, i & 4 ? kHalf : -kHalf);
}

// One loaded edge along x (two vertices below the floor at equal depth δ, lever r_y): the
// proxy's torque is τ_x = k_r δ r_y/(R_w + r_y²) (eq. 3.2–3.5 in closed form, as in T3.1).
// Returns false for any
// other contact state.
bool EdgeTorque(const ProxyTick& tick, double k_r, double R_w, double* tau) {
  constexpr double kSame = 1e-12;  // equal depths to rounding of metre-scale poses
  std::vector<Vec3> below;
  for (int i = 0; i < 8; ++i) {
    const Vec3 v = tick.X_WP * Vertex(i);
    if (v.z() < 0.0) below.push_back(v);
  }
  if (below.size() != 2 || std::abs(below[0].z() - below[1].z()) > kSame ||
      std::abs(below[0].y() - below[1].y()) > kSame) {
    return false;
  }
  const double lever = below[0].y() - tick.X_WP.p.y();
  *tau = k_r * -below[0].z() * lever / (R_w + lever * lever);
  return true;
}

bool Constrained(const ProxyTick& tick, const Vec3& vertex) {
  for (const Vec3& p : tick.constrained_p_PV) {
    if ((p - vertex).norm() < kSameVertex) return true;
  }
  return false;
}

// Penetration of the cube's vertices below the floor (z = 0) at the proxy pose.
void Penetration(const ProxyTick& tick, SweepPoint* point) {
  for (int i = 0; i < 8; ++i) {
    const Vec3 b = Vertex(i);
    const double depth = -(tick.X_WQ * b).z();
    if (Constrained(tick, b)) {
      point->bound_penetration = std::max(point->bound_penetration, depth);
    } else if (depth > point->free_penetration) {
      point->free_penetration = depth;
      point->free_penetration_time = tick.t;
    }
  }
}

SweepPoint Measure(double multiplier, const ProxyRun& run, const settings::RenderingSettings& r) {
  SweepPoint p;
  p.multiplier = multiplier;
  p.R_w = multiplier * (2.0 * kHalf) * (2.0 * kHalf) / 6.0;  // unit-mass cube inertia a²/6
  p.peak_torque_analytic = r.rot_stiffness * kEdgeDepth * kHalf / (p.R_w + kHalf * kHalf);
  int rolling = 0;
  double sweeps = 0.0;
  for (std::size_t i = 0; i < run.ticks.size(); ++i) {
    const ProxyTick& tick = run.ticks[i];
    Penetration(tick, &p);
    const double tau = tick.w_W.tau.norm();
    p.max_torque = std::max(p.max_torque, tau);
    sweeps += tick.diagnostics.iterations;
    if (!tick.diagnostics.converged) ++p.unconverged;
    double tau_an = 0.0;
    if (In(tick.t, kRoll) && tick.diagnostics.converged && tick.diagnostics.contacts == 2 &&
        EdgeTorque(tick, r.rot_stiffness, p.R_w, &tau_an)) {
      ++p.edge_ticks;
      p.edge_torque_error = std::max(p.edge_torque_error, std::abs(tick.w_W.tau.x() - tau_an));
      if (tau > p.edge_peak_torque) {
        p.edge_peak_torque = tau;
        p.edge_peak_analytic = std::abs(tau_an);
      }
    }
    if (In(tick.t, kRoll)) {
      ++rolling;
      p.peak_torque = std::max(p.peak_torque, tau);
      p.mean_torque += tau;
    }
    if (i > 0 && In(tick.t, kTransition)) {
      const ProxyTick& before = run.ticks[i - 1];
      p.force_jump = std::max(p.force_jump, (tick.w_W.f - before.w_W.f).norm());
      p.torque_jump = std::max(p.torque_jump, (tick.w_W.tau - before.w_W.tau).norm());
    }
  }
  p.mean_torque /= std::max(rolling, 1);
  p.mean_sweeps = sweeps / static_cast<double>(std::max<std::size_t>(run.ticks.size(), 1));
  return p;
}

// t3_5.csv: one row per multiplier.
Table CsvTable(const std::vector<SweepPoint>& points) {
  Table csv({"multiplier", "R_w_m2", "free_vertex_penetration_mm", "at_t_s",
             "constrained_vertex_penetration_mm", "roll_peak_torque_Nm",
             "roll_peak_torque_analytic_Nm", "roll_mean_torque_Nm", "max_torque_Nm",
             "transition_max_force_jump_N", "transition_max_torque_jump_Nm", "mean_pgs_sweeps",
             "unconverged_ticks"});
  for (const SweepPoint& p : points) {
    csv.AddFormatted(
        "{},{:.6g},{:.6f},{:.3f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},"
        "{:.1f},{}",
        p.multiplier, p.R_w, p.free_penetration * 1e3, p.free_penetration_time,
        p.bound_penetration * 1e3, p.peak_torque, p.peak_torque_analytic, p.mean_torque,
        p.max_torque, p.force_jump, p.torque_jump, p.mean_sweeps, p.unconverged);
  }
  return csv;
}

// t3_5.md: the printed subset of t3_5.csv.
Table MarkdownTable(const std::vector<SweepPoint>& points) {
  Table md({"multiplier", "R_w (m²)", "free-vertex penetration (mm)", "peak roll torque (N·m)",
            "mean roll torque (N·m)", "max Δτ/tick in transition (N·m)"});
  for (const SweepPoint& p : points) {
    md.Add({fmt::format("{}", p.multiplier), fmt::format("{:.4g}", p.R_w),
            fmt::format("{:.4f}", p.free_penetration * 1e3), fmt::format("{:.4f}", p.peak_torque),
            fmt::format("{:.4f}", p.mean_torque), fmt::format("{:.4f}", p.torque_jump)});
  }
  return md;
}

constexpr const char* kPlot =
    "# Thesis fig. 3.18: rotation weight too small -> unconstrained vertices penetrate,\n"
    "# too large -> weak torque. Re-run with: gnuplot t3_5.gp\n"
    "set terminal pngcairo size 1000,800 enhanced font ',11'\nset output 't3_5.png'\n"
    "set datafile separator ','\nset grid\nset logscale x\nset key top right\n"
    "set xlabel 'multiplier on the unit-mass inertia (R_w = m a^2/6)'\n"
    "set multiplot layout 2,1 title 'T3.5: rotation-weight sweep on the T3.1 motion "
    "(k_t = k_r = 9000)'\n"
    "set ylabel 'penetration at the proxy (mm)'\n"
    "plot 't3_5.csv' using 1:3 with linespoints lw 2 title 'unconstrained vertices', "
    "'' using 1:5 with linespoints dt 2 title 'constrained vertices'\n"
    "set logscale y\nset ylabel 'torque (N m)'\n"
    "plot 't3_5.csv' using 1:6 with linespoints lw 2 title 'peak while rolling', "
    "'' using 1:7 with lines dt 2 title 'analytic single-edge peak', "
    "'' using 1:11 with linespoints title 'max |{/Symbol D}{/Symbol t}| per tick, edge "
    "-> face'\nunset multiplot\n";

// Writes t3_5.csv, t3_5.md and t3_5.png; returns the markdown table.
std::string WriteT35Files(const std::filesystem::path& out, const std::vector<SweepPoint>& points,
                          bool quiet) {
  WriteText(out / "t3_5.csv", CsvTable(points).Csv());
  const std::string md = MarkdownTable(points).Markdown();
  WriteText(out / "t3_5.md", md);
  Plot(out, "t3_5", kPlot, quiet);
  return md;
}

// Thesis §3.4.1 (fig. 3.18) trends: the displayed torque falls as R_w grows (and follows the
// analytic single-edge peak), and a small R_w lets unconstrained vertices penetrate more than a
// large one. The analytic comparison uses the ticks where PGS converged with one edge loaded; its
// tolerance is T3.1's: a displacement error of at most m·κ·tol (κ = R_w/h², m = 2 rows) turns
// into k_r·m·κ·tol·√2·h/R_w = k_r·2·tol·√2/h of torque.
Checks CheckT35(const std::vector<SweepPoint>& points, const settings::RenderingSettings& r) {
  const double tau_tol = r.rot_stiffness * 2.0 * r.solver_tolerance * std::sqrt(2.0) / kHalf;
  bool torque_follows = true, torque_falls = true;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SweepPoint& p = points[i];
    torque_follows = torque_follows && p.edge_ticks > 0 && p.edge_torque_error <= tau_tol;
    if (i > 0) torque_falls = torque_falls && p.peak_torque < points[i - 1].peak_torque;
  }
  const bool penetration =
      points.size() >= 2 && points.front().free_penetration > points.back().free_penetration;
  Checks checks;
  checks.Add("one_edge_torque_matches_analytic", torque_follows);
  checks.Add("torque_falls_as_rotation_weight_grows", torque_falls);
  checks.Add("small_weight_penetrates_more_than_large", penetration);
  return checks;
}

}  // namespace

int RunT35(const std::filesystem::path& out, bool quiet) {
  return RunT35(out, quiet, T35Options{});
}

int RunT35(const std::filesystem::path& out, bool quiet, const T35Options& options) {
  std::filesystem::create_directories(out);
  const std::filesystem::path file = ScenesDir() / "t3_5.json";
  session::Session session = session::LoadSession(file);
  std::vector<SweepPoint> points;
  for (const double multiplier : options.multipliers) {
    session.engine.rendering.rotation_weight.reset();
    session.engine.rendering.rotation_weight_scale = multiplier;
    if (!quiet) std::cout << fmt::format("t3.5: multiplier {}...\n", multiplier);
    const ProxyRun run = RunProxySession(session, {}, "", quiet);
    points.push_back(Measure(multiplier, run, session.engine.rendering));
  }
  const std::string table = WriteT35Files(out, points, quiet);
  nlohmann::json summary;
  summary["experiment"] = "t3.5";
  summary["machine"] = MachineTag();
  for (const SweepPoint& p : points) {
    summary["points"].push_back({{"multiplier", p.multiplier},
                                 {"R_w_m2", p.R_w},
                                 {"free_vertex_penetration_m", p.free_penetration},
                                 {"roll_peak_torque_Nm", p.peak_torque},
                                 {"one_edge_peak_torque_Nm", p.edge_peak_torque},
                                 {"one_edge_peak_torque_analytic_Nm", p.edge_peak_analytic},
                                 {"one_edge_ticks_compared", p.edge_ticks},
                                 {"one_edge_max_torque_error_Nm", p.edge_torque_error},
                                 {"roll_mean_torque_Nm", p.mean_torque},
                                 {"transition_max_torque_jump_Nm", p.torque_jump},
                                 {"unconverged_ticks", p.unconverged}});
  }
  if (!quiet) std::cout << table;
  return FinishExperiment(out, summary, CheckT35(points, session.engine.rendering), quiet);
}

}  // namespace mrh::experiments::internal
