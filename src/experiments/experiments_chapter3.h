// SPDX-License-Identifier: Apache-2.0
// The chapter-3 experiment drivers (method proxy-6dof) behind mrh::experiments::Run: t3.1,
// t3.2, t3.4 to t3.7 and the proxy-6dof session runs they share.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/engine/engine.h"
#include "mrh/render/proxy_renderer.h"

namespace mrh::session {
struct Session;
}

namespace mrh::experiments::internal {

/// One case × method of t3.6: rendered |f| and |τ| statistics over 2–5 s, peak |ω|
/// of any box after a global step, every box's COM at 4 s.
struct T36Result {
  std::string case_name;
  std::string method;                   ///< e.g. "local-dynamics-6dof@20ms"
  double mean_f = 0.0, sd_f = 0.0;      ///< N
  double mean_tau = 0.0, sd_tau = 0.0;  ///< N·m, of |τ|
  Vec3 mean_tau_W = Vec3::Zero();       ///< N·m, mean rendered torque vector (world)
  double sliding_f = 0.0;               ///< N, Coulomb's μ Σm |g| if the boxes slide, else 0
  double peak_spin = 0.0;               ///< rad/s
  double peak_speed = 0.0;              ///< m/s, the boxes' COM
  std::vector<Vec3> pose_at;            ///< m, world, each box's COM at 4 s
  double yaw_at = 0.0;                  ///< rad, the first box's heading about +z at 4 s
};

/// Runs t3.6's cases (face, offcentre, tip, wall, row, edge) × the reference (virtual coupling
/// at 1 ms, first), proxy-6dof at 1 and 20 ms, local-dynamics-6dof at 20 ms, then the reference
/// and local-dynamics-6dof with the pointer nudged 10 µm to −y and +y; runs/ CSVs under `out`;
/// results[case][method].
std::vector<std::vector<T36Result>> RunT36Cases(const std::filesystem::path& out, bool quiet);

/// t3.6: returns 0 if every check passes (nothing thrown; Coulomb's force in steady slides; the
/// off-centre push follows the reference; local-dynamics-6dof is robust to a 10 µm nudge).
int RunT36(const std::filesystem::path& out, bool quiet);

/// What t3.7 runs: the shape matrix (scenes/t3_7_*.xml) × pointers × centred and off-centre
/// pushes, each with virtual coupling at 1 ms (the reference), proxy-6dof at 1 and 20 ms and
/// local-dynamics-6dof at 20 ms.
struct T37Options {
  std::vector<std::string> shapes;              ///< empty: all six
  std::vector<std::string> pointers = {"box"};  ///< "box", "sphere"
  bool offcentre = true;  ///< also push off centre (box pointer 4 cm, sphere 2 cm)
};

/// One t3.7 run's figures (statistics window 2–5 s; peaks from the touch at 1 s).
struct T37Result {
  std::string shape, pointer, method;  ///< method: e.g. "local-dynamics-6dof@20ms"
  bool offcentre = false;
  double mean_f = 0.0;          ///< N, rendered |f| over 2–5 s
  double sd_f = 0.0;            ///< N, its standard deviation over 2–5 s
  Vec3 impulse = Vec3::Zero();  ///< N·s, ∫f dt of the rendered force from the touch on (world)
  double coulomb_f = 0.0;       ///< N, μ m |g| where the push is a steady slide, else 0
  double rolling_radius = 0.0;  ///< m, where the object rolls, else 0
  double peak_speed = 0.0;      ///< m/s, the object's COM
  double peak_spin = 0.0;       ///< rad/s
  Vec3 end = Vec3::Zero();      ///< m, COM at the end (world)
  double yaw = 0.0;             ///< rad, heading of the body's x axis about +z at the end
};

/// A run judged by the acceptance bars against the analytic expectations and the reference run
/// of its case (virtual coupling at 1 ms). Unset optionals: the bar does not apply.
struct T37Verdict {
  /// m/s: 2.5× the larger of the pointer's speed and the reference's peak speed.
  double speed_bound = 0.0;
  bool thrown = false;  ///< peak speed above speed_bound
  /// rad/s, rolling bodies: 2.5× the larger of v / r and the reference's peak spin.
  std::optional<double> spin_bound;
  bool spun = false;                  ///< peak spin above spin_bound
  std::optional<double> slide_error;  ///< mean |f| / μ m g − 1 (steady slides)
  std::optional<bool> slide_ok;       ///< |slide_error| ≤ 5 %
  /// Off-centre, sliding: |J − J_ref| / |J_ref| of the impulses J = ∫f dt.
  std::optional<double> force_vs_ref;
  std::optional<double> pose_error;  ///< off-centre, sliding: m, end (x, y) from the reference's
  std::optional<bool> follows_ref;   ///< pose_error ≤ 2 cm and |force_vs_ref| ≤ 10 %
  std::optional<bool> same_turn;     ///< off-centre, sliding, the reference turned ≥ 5°
};

T37Verdict Judge(const T37Result& r, const T37Result& ref);

/// Runs the matrix; results in case order, kVariants' order within a case (reference first).
std::vector<T37Result> RunT37Cases(const std::filesystem::path& out, bool quiet,
                                   const T37Options& options);

/// t3.7 with the box pointer (`--full`: box and sphere pointers). Returns 0 if every check
/// passes: nothing thrown; local-dynamics-6dof and proxy-6dof at 1 ms within the analytic bars;
/// local-dynamics-6dof following the reference off centre.
int RunT37(const std::filesystem::path& out, bool quiet);
int RunT37(const std::filesystem::path& out, bool quiet, const T37Options& options);
int RunT37Full(const std::filesystem::path& out, bool quiet);

/// One haptic tick of a proxy-6dof run as the chapter-3 drivers see it (world frame).
struct ProxyTick {
  double t = 0.0;                        ///< s
  Pose X_WP;                             ///< pointer
  Wrench w_W;                            ///< rendered wrench (before the safety layer)
  Pose X_WQ;                             ///< proxy
  Vec3 dr = Vec3::Zero();                ///< Δr, proxy − pointer translation (m)
  Vec3 dtheta = Vec3::Zero();            ///< Δθ, proxy rotation vector from the pointer (rad)
  render::ProxyDiagnostics diagnostics;  ///< rows, friction states, PGS sweeps
  std::vector<Vec3> constrained_p_PV;    ///< pointer-frame points with a normal row this tick
};

/// A proxy-6dof session run: the engine's statistics and one ProxyTick per haptic tick.
struct ProxyRun {
  engine::RunStats stats;
  std::vector<ProxyTick> ticks;
};

/// Runs `session` (method proxy-6dof) in lockstep with the engine's own scheduler, sampling the
/// method after every tick. When `dir` is not empty, writes ticks.csv, bodies.csv, steps.csv,
/// summary.json and report.png there (a gnuplot failure is a warning unless `quiet`).
/// @throws mrh::InvalidArgument if the session's method is not proxy-6dof. Defined in t3_1.cc.
ProxyRun RunProxySession(const session::Session& session, const std::filesystem::path& dir,
                         const std::string& title, bool quiet);

/// T3.1's session (same device motion) run with method penalty-sum (B5) in lockstep through the
/// public engine API: one record per tick. Defined in t3_1_penalty_sum.cc.
std::vector<ir::TickRecord> RunPenaltySumTicks(const session::Session& session);

/// The T3.1 windows the penalty-sum check reads: k (N/m), the held edge/face depths (m), the
/// edge hold [t0, t1) and the time after which the face is held (s).
struct PenaltySumWindows {
  double k = 0.0, edge_depth = 0.0, face_depth = 0.0;
  double edge_hold[2] = {0.0, 0.0};
  double face_hold = 0.0;
};

/// B5 vs the proxy (Berkelman & Hollis 2000, thesis ref. [43]): checks the sum renders 2kδ on
/// the held edge and 4kδ on the
/// held face (the proxy: k_t δ on both), and writes the forces and force-per-depth stiffnesses
/// into `numbers`. Returns the checks.
nlohmann::json CheckPenaltySumT31(const std::vector<ir::TickRecord>& ticks,
                                  const PenaltySumWindows& windows, nlohmann::json* numbers);

/// T3.1: edge contact → roll → face contact of a 0.2 m cube at the thesis gains (figs.
/// 3.10–3.11). Returns 0 if the analytic checks pass.
int RunT31(const std::filesystem::path& out, bool quiet);

/// T3.2: friction strokes and twist with μ = 0.5 (figs. 3.13–3.14). Returns 0 if the checks
/// pass (kinetic |f_t| = μ|f_n|, static below, friction against the motion).
int RunT32(const std::filesystem::path& out, bool quiet);

/// T3.4: haptic tick time vs contact points (N-gon prism sliding on a floor), with and without
/// friction (fig. 3.17). Returns 0 if every run had N contacts and finite timings.
int RunT34(const std::filesystem::path& out, bool quiet);

/// What RunT34 runs.
struct T34Options {
  std::vector<int> sides = {5, 10, 20, 50, 100, 200, 500, 1000};
  double duration = 2.0;  ///< s simulated per run (ticks = duration / 1 ms)
};

int RunT34(const std::filesystem::path& out, bool quiet, const T34Options& options);

/// T3.5: rotation-weight sweep on the T3.1 motion: penetration of unconstrained vertices and
/// torque vs the multiplier on the unit-mass inertia (fig. 3.18). Returns 0 if the trends hold.
int RunT35(const std::filesystem::path& out, bool quiet);

/// What RunT35 runs.
struct T35Options {
  std::vector<double> multipliers = {1, 3, 10, 30, 100, 300, 500, 1000, 3000, 10000};
};

int RunT35(const std::filesystem::path& out, bool quiet, const T35Options& options);

}  // namespace mrh::experiments::internal
