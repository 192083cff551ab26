// SPDX-License-Identifier: Apache-2.0
// The experiment drivers behind mrh::experiments::Run.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/engine/engine.h"
#include "mrh/physics/method_physics.h"
#include "mrh/render/proxy_renderer.h"

namespace mrh::session {
struct Session;
}

namespace mrh::ir {
struct PhysicsSnapshot;
}

namespace mrh::engine {
class Method;
}

namespace mrh::experiments::internal {

/// T3.3 (thesis §3.3.4): real-time computation ratio per method and cube count (rows of 3 resting
/// cubes, the first row pushed by a box pointer). Lockstep; a method's ratio is its mean haptic
/// compute per tick (run wall time − physics step time, over the ticks: engine bookkeeping
/// included) / 1 ms plus its p50 physics step / physics_dt (20 ms; 1 ms for the single-rate
/// contact-volume and virtual-coupling, whose step is their haptic loop); the p99 step gives
/// ratio_p99 and max_realtime_cubes_p99 (on a shared VM the p99 is mostly its stalls). Returns 0 if
/// every ratio is finite, proxy-6dof is cheaper than contact-volume at every count and
/// contact-volume's ratio grows from the smallest to the largest count.
struct T33Options {
  std::vector<std::string> methods = {"proxy-6dof", "contact-volume", "virtual-coupling",
                                      "penalty-sum"};
  std::vector<int> cubes = {3, 9, 18};  ///< to_limit: the first count only
  double duration = 0.3;                ///< s simulated per run
  /// Grow each method's cube count from cubes.front() (by 3 up to 30, then by half) until its
  /// ratio passes 1 or the count passes max_cubes; summary["limit"] has each method's maximum.
  bool to_limit = false;
  int max_cubes = 600;  ///< the scene-size limit of to_limit
};

/// Where a method's real-time computation ratio passes 1 as the cube count grows.
struct T33Limit {
  int max_realtime = 0;  ///< largest measured count with ratio ≤ 1 (0: none)
  int first_over = 0;  ///< first measured count with ratio > 1 (0: the scene-size limit came first)
};

/// Measures ratio(n) for n = first (rounded down to a multiple of 3, at least 3), +3 up to 30,
/// then ×1.5 (to a multiple of 3), until a ratio passes 1 or n passes max_cubes.
T33Limit GrowToLimit(int first, int max_cubes, const std::function<double(int)>& ratio);

int RunT33(const std::filesystem::path& out, bool quiet);
int RunT33(const std::filesystem::path& out, bool quiet, const T33Options& options);
/// `mrh experiment t3.3 --full`: every method to its limit (GrowToLimit from 3 cubes, 1 s per run).
int RunT33Full(const std::filesystem::path& out, bool quiet);

/// T4.1: single-rate, impulse and local-dynamics on the moving 60 kg cube, plus a mass × speed
/// sweep of the impulse error. Returns 0 if its checks pass.
int RunT41(const std::filesystem::path& out, bool quiet);

/// What RunT41 runs (tests run subsets).
struct T41Options {
  std::vector<std::string> methods = {"single-rate", "impulse", "local-dynamics"};
  bool sweep = true;  ///< also sweep mass (15–240 kg) × speed (0.005–0.1 m/s)
};

int RunT41(const std::filesystem::path& out, bool quiet, const T41Options& options);

/// T4.2: the 2AFC mass study (scenes/t4_2.json) with simulated observers through
/// psychophysics::RunStudy and the psychometric analysis. Returns 0 if its checks pass.
int RunT42(const std::filesystem::path& out, bool quiet);

/// What RunT42 runs.
struct T42Options {
  std::vector<std::string> observers = {"A", "B", "C", "D", "E"};
  int trials_per_mass = 0;           ///< 0: the session's (20)
  double weber = 0.10;               ///< Weber fraction of the observers' momentum percept
  std::uint64_t observer_seed = 42;  ///< observer i draws its noise from seed + i
  /// Simulate each distinct stimulus once and reuse its momentum (the lockstep world is
  /// deterministic, so repeated presentations are identical); false re-simulates every one.
  bool cache = true;
};

int RunT42(const std::filesystem::path& out, bool quiet, const T42Options& options);

/// Per-call timings of a method wrapped by RegisterTimedMethod (filled on the calling threads).
struct MethodTimings {
  /// Called on the physics side with each snapshot PhysicsStep produced (optional).
  std::function<void(const ir::PhysicsSnapshot&)> on_snapshot;
  /// Called on the physics side after each PhysicsStep with the wrapped method (optional), to
  /// read its counters.
  std::function<void(const physics::MethodPhysics&)> on_step;
  std::vector<double> step_wall_ms;   ///< PhysicsStep wall time (ms)
  std::vector<double> step_cpu_ms;    ///< PhysicsStep thread CPU time (ms): immune to preemption
  std::vector<double> tick_wall_us;   ///< HapticTick wall time (µs)
  std::vector<int> tick_j;            ///< TickInput::j of each tick
  std::vector<int> tick_contacts;     ///< TickOutput::contacts of each tick
  std::vector<double> adopt_wall_us;  ///< Adopt wall time (µs)
  std::vector<double> end_period_wall_us;  ///< EndPeriod wall time (µs)
};

/// Registers method "timed:<inner>", which forwards every call to a new `inner` method and
/// appends the timings to `*sink`, and returns that name. Vectors are reserved for `max_ticks`
/// ticks and `max_steps` steps (the haptic half never allocates until they are full; beyond
/// that, timings are dropped). The engine measures only the wall time of whole physics steps;
/// this adds CPU time and per-tick cost without changing the engine. Not RT-safe to register.
std::string RegisterTimedMethod(const std::string& inner, std::shared_ptr<MethodTimings> sink,
                                std::size_t max_ticks, std::size_t max_steps);

/// T4.3: computation occupancy (physics step compute time / physics_dt) per method and cube
/// count. Returns 0 if every run produced finite occupancies for every step, every
/// local-dynamics test-force run was solved on its constraint island (no MuJoCo solver
/// iterations: a count, independent of timing) and the island accelerance agrees with a
/// converged MuJoCo measurement to 1e-4 (accuracy runs at the largest cube count).
int RunT43(const std::filesystem::path& out, bool quiet);

/// What RunT43 runs. A variant is a method name, or "local-dynamics/no-perturbation"
/// (rendering.perturbation = false).
struct T43Options {
  std::vector<std::string> variants = {"single-rate", "impulse", "local-dynamics",
                                       "local-dynamics/no-perturbation"};
  std::vector<int> cubes = {1, 10, 100};  ///< frictionless (condim 1) runs
  /// Runs with friction (condim 3, μ = 1, pyramidal cones), file and summary keys
  /// "<cubes>_friction".
  std::vector<int> friction_cubes = {1, 10, 100};
  double physics_dt = 0.02;      ///< s, multi-rate methods (single-rate steps at haptic_dt)
  int steps = 50;                ///< physics steps per multi-rate run
  int single_rate_steps = 1000;  ///< physics steps (1 ms each) per single-rate run
  /// Physics steps of the accuracy run at the largest cube count: local-dynamics whose every
  /// measurement is repeated with the exact warm start (TestRunWarmStart::kSaved). 0: none.
  int accuracy_steps = 5;
};

int RunT43(const std::filesystem::path& out, bool quiet, const T43Options& options);
/// `mrh experiment t4.3 --full`: 1-1000 cubes frictionless, 1-500 with friction.
int RunT43Full(const std::filesystem::path& out, bool quiet);

/// T4.4: a cube pushed into a line of cubes (felt mass steps up as each joins) and a cube pushed
/// near an edge (it turns). Returns 0 if the checks pass for local-dynamics.
int RunT44(const std::filesystem::path& out, bool quiet);

/// What RunT44 runs.
struct T44Options {
  std::vector<std::string> variants = {"local-dynamics", "single-rate", "impulse",
                                       "local-dynamics/no-perturbation"};
};

int RunT44(const std::filesystem::path& out, bool quiet, const T44Options& options);

/// T4.5: neighbors simulated locally vs haptic tick cost and physics occupancy. Returns 0 if
/// local-dynamics simulated and rendered every neighbor with finite timings.
int RunT45(const std::filesystem::path& out, bool quiet);

/// What RunT45 runs.
struct T45Options {
  /// The impulse method is unstable on this scene (k = 1000 N/m on 0.1 kg balls at 50 ms):
  /// add it to see its cost with the balls flung off.
  std::vector<std::string> methods = {"local-dynamics"};
  std::vector<int> neighbors = {1, 2, 4, 8, 16, 32, 64, 128};
  double duration = 1.0;  ///< s simulated per run
};

int RunT45(const std::filesystem::path& out, bool quiet, const T45Options& options);

/// T4.6 (thesis §4.6.3): a body's 6×6 accelerance (and the 3×3 point accelerance) estimated
/// by the thesis' 1 + 18 perturbation runs, its 2-run estimate, the analytic island estimate
/// and the thesis' 3-DOF 1 + 3 runs, against converged MuJoCo on a free box (zero gravity), a
/// box resting on a floor (pushed, sticking; pushed harder, sliding) and a box pushed into a
/// row; cost per physics step and occupancy with `cubes` cubes (t4.3's scene with friction).
/// Returns 0 if the checks pass.
struct T46Options {
  std::vector<int> cubes = {10};
  int repetitions = 10;  ///< timed physics steps per cube count (medians)
};

int RunT46(const std::filesystem::path& out, bool quiet);
int RunT46(const std::filesystem::path& out, bool quiet, const T46Options& options);
/// `mrh experiment t4.6 --full`: 10 and 100 cubes, 30 repetitions.
int RunT46Full(const std::filesystem::path& out, bool quiet);

/// Latency from the user's force onset to the touched object's response, in haptic ticks, per
/// method and onset phase within the physics period. Returns 0 if the checks pass.
int RunLatency(const std::filesystem::path& out, bool quiet);

/// What RunLatency runs.
struct LatencyOptions {
  std::vector<std::string> methods = {"local-dynamics", "impulse", "single-rate"};
  /// Tick of the physics period at which contact starts (0 .. n−1).
  std::vector<int> onset_phases = {0, 25, 49};
};

int RunLatency(const std::filesystem::path& out, bool quiet, const LatencyOptions& options);

/// A t4.push case: scene scenes/t4_push_<scene or name>.xml, pointer height z (m),
/// the time the pointer stops pushing (s), the run length (s), the pointer's lateral offset y
/// (m) and whether local-dynamics is held to the acceptance bars on it (`checked`; false for the
/// pyramidal-cone box, on which single-rate's straight push is unstable).
struct PushCase {
  std::string name;
  double z = 0.05;
  double push_until = 6.0;
  double duration = 6.0;
  double y = 0.0;
  bool checked = true;
  std::string scene;  ///< empty: name
};

/// What RunT4Push runs; methods[0] must be single-rate (the reference).
struct PushOptions {
  std::vector<PushCase> cases;
  std::vector<std::string> methods = {"single-rate", "local-dynamics",
                                      "local-dynamics/perturbation", "impulse"};
};

/// One case × method of t4.push: |f| statistics over 2–5 s, box COM at 5 s, peak |ω|.
struct PushResult {
  double mean_force = 0.0;       ///< N
  double sd_force = 0.0;         ///< N
  double contact_lost = 0.0;     ///< share of ticks with |f| = 0
  Vec3 position = Vec3::Zero();  ///< m
  double peak_spin = 0.0;        ///< rad/s
};

/// The acceptance cases (one box, heavy box, row of three, wall, tip), plus the row's two
/// chaos probes (10 µm lateral pointer offsets) and the row between rails (row_guided).
PushOptions DefaultPushOptions();

/// Runs every case × method (runs/ CSVs under `out`); results[case][method].
std::vector<std::vector<PushResult>> RunPushCases(const std::filesystem::path& out,
                                                  const PushOptions& options, bool quiet);

/// t4.push: returns 0 if local-dynamics meets the acceptance bars against single-rate in every
/// case (mean within 5 %, sd <= max(2x, 2 % of mean), contact loss <= single-rate's, box within
/// 2 cm at 5 s).
int RunT4Push(const std::filesystem::path& out, bool quiet);
int RunT4Push(const std::filesystem::path& out, bool quiet, const PushOptions& options);

/// One run of the grasp experiment: a method at its physics step.
struct GraspRun {
  std::string method = "single-rate";
  double physics_dt = 0.001;  ///< s
};

/// The runs of every grasp case: the reference (single-rate at 1 ms) first, then the methods at
/// 20 ms: the local-dynamics methods (checked against the acceptance bars) and proxy-6dof and
/// impulse (reported: their reaction arrives one physics step late).
std::vector<GraspRun> GraspRuns();

/// True for the 20 ms runs held to the bars (local-dynamics, local-dynamics-6dof).
bool GraspChecked(const GraspRun& run);

/// "local-dynamics-6dof" → "local_dynamics_6dof": a method name as a check-name part.
std::string CheckName(const std::string& method);

/// What a grasp run measured over the hold (both fingers still, box lifted).
struct GraspResult {
  double hold_height = 0.0;           ///< box COM's mean rise above its start (m)
  double mean_force[2] = {0.0, 0.0};  ///< each finger's mean |displayed force| (N)
  double sd_force[2] = {0.0, 0.0};    ///< and its standard deviation (N)
  double mean_lift_force = 0.0;       ///< −Σ fingers' mean f_z: the weight they carry (N)
  double box_mass = 0.0;              ///< kg (the scene's)
};

/// Runs scenes/two_finger_grasp.xml with two simulated hands on a device::PinchKeyframes pinch
/// (close, lift 5 cm, hold, lower, open); writes runs/<method>_{force,box}.csv under `out` when
/// `out` is not empty.
GraspResult RunGraspCase(const std::filesystem::path& out, const GraspRun& run);

/// The acceptance bars for a grasp run against the reference: hold height within 5 mm, each
/// finger's mean force within 5 % and its standard deviation at most 2x the reference's.
bool MeetsBars(const GraspResult& r, const GraspResult& reference);

/// The bars on both fingers of a grasp case: each finger's mean force within 5 % of the
/// reference's and its standard deviation at most 2x the reference's.
bool FingersMeetBars(const double mean[2], const double sd[2], const double ref_mean[2],
                     const double ref_sd[2]);

/// What the two-hands case measured over the steady slide (2–4 s). Index 0 is the left hand
/// (its 0.5 kg box), 1 the right (0.3 kg).
struct HandsResult {
  double mean_force[2] = {0.0, 0.0};  ///< each hand's mean |displayed force| (N); 0 if absent
  double sd_force[2] = {0.0, 0.0};    ///< and its standard deviation (N)
  double coulomb[2] = {0.0, 0.0};     ///< μ m g of each hand's box (N, the scene's μ and mass)
  double travel[2] = {0.0, 0.0};      ///< each box's travel along its hand's push by the end (m)
};

/// Runs scenes/two_hands_push.xml: scripted hands `hands` (0 left, 1 right; both, or one alone)
/// start between the boxes and push each its own box outward at 0.1 m/s, touching it at 1 s.
/// Writes runs/hands_<method>[_<hand>_alone]_{force,box}.csv under `out` unless it is empty.
HandsResult RunHandsCase(const std::filesystem::path& out, const GraspRun& run,
                         const std::vector<int>& hands);

class Checks;

/// The two-hands case of RunGrasp: runs it, writes grasp_hands.csv and grasp_hands.png, appends
/// its table to `md` and adds its checks and summary["hands"].
void RunGraspHands(const std::filesystem::path& out, bool quiet, std::string* md, Checks* checks,
                   nlohmann::json* summary);

/// What the slide case measured while the fingers drag the box (1.1–1.8 s).
struct SlideResult {
  double mean_force[2] = {0.0, 0.0};  ///< each finger's mean |displayed force| (N)
  double sd_force[2] = {0.0, 0.0};    ///< and its standard deviation (N)
  double push_force = 0.0;            ///< −Σ fingers' mean f_x: what drags the box (N)
  double carried = 0.0;  ///< −Σ fingers' mean f_z: the weight they take off the floor (N)
  /// Coulomb's sliding friction on the box, μ_floor (m g − carried) (N).
  double coulomb = 0.0;
  double box_travel = 0.0;      ///< box COM's x displacement at the end of the hold (m)
  double fingers_travel = 0.0;  ///< the fingers' scripted travel (m)
  double box_mass = 0.0;        ///< kg (the scene's)
  double floor_mu = 0.0;        ///< the scene's box–floor μ
};

/// Runs scenes/two_finger_slide.xml: two simulated hands grip the box as in the lift case, then
/// move 0.1 m along +x at 0.1 m/s, hold and let go. Writes runs/slide_<method>_{force,box}.csv
/// under `out` unless it is empty.
SlideResult RunSlideCase(const std::filesystem::path& out, const GraspRun& run);

/// The lift case's bars on the slide: each finger's mean force within 5 % of the reference's, its
/// sd at most 2x the reference's, the box's travel within 5 mm of the reference's.
bool MeetsSlideBars(const SlideResult& r, const SlideResult& reference);

/// The slide case of RunGrasp: runs it, writes grasp_slide.csv and grasp_slide.png, appends its
/// table to `md` and adds its checks and summary["slide"].
void RunGraspSlide(const std::filesystem::path& out, bool quiet, std::string* md, Checks* checks,
                   nlohmann::json* summary);

/// grasp: three cases, single-rate at 1 ms (the reference) against local-dynamics and
/// local-dynamics-6dof (checked), proxy-6dof and impulse (reported) at 20 ms. Lift: the pinch, lift
/// and hold (grasp.csv, grasp.png). Two hands: each hand pushes its own box apart from the other's,
/// together and each alone (grasp_hands.csv, grasp_hands.png). Slide: the squeezed box dragged
/// sideways (grasp_slide.csv, grasp_slide.png). Also grasp.md (every table and the checks) and
/// summary.json; returns 0 if every check passes: the reference lifts and holds the box and
/// local-dynamics meets the lift bars; each hand feels its box's μ m g within 5 % and its force
/// alone within 5 %, in the reference and in local-dynamics; the reference's slide drags the box
/// with Coulomb's force within 5 % and local-dynamics meets the slide bars.
int RunGrasp(const std::filesystem::path& out, bool quiet);

/// Demo D1 (thesis §4.6.4): scenes/d1.json, a simulated hand sweeping through
/// 80 objects of four shapes on a table with local-dynamics. First a lockstep run with the hand
/// held above the table (the objects must stay at rest), then the session itself, then (by
/// default) the same hand path with the single-rate reference. Checks: the
/// objects stay on the table, the hand touches them, no object is faster than the speed the
/// hand and gravity can give it, no warnings or faults, peak RSS < 300 MB; in real time also
/// the acceptance bars (haptic rate >= 990 Hz, overruns <= 0.5 % of ticks, step p99 < physics_dt).
/// Writes d1.csv (per physics step), d1.md, d1.png and summary.json; returns 0 if every check
/// passes.
struct D1Options {
  bool realtime = true;        ///< false: lockstep (deterministic; timings not checked)
  double duration = 10.0;      ///< s; beyond the 10 s hand path, the path repeats every 11 s
  double rest_duration = 2.0;  ///< s of the hand held above the table
  /// Also run the 10 s hand path with the single-rate reference (MuJoCo at 1 ms, lockstep) and
  /// check that its objects stay on the table within the same speed bound.
  bool reference = true;
};

int RunD1(const std::filesystem::path& out, bool quiet);
int RunD1(const std::filesystem::path& out, bool quiet, const D1Options& options);
/// `mrh experiment d1 --full`: 60 s in real time.
int RunD1Full(const std::filesystem::path& out, bool quiet);

/// Demo D3, material display: scenes/d3.json's aluminium, wood and rubber blocks each tapped at
/// 0.05, 0.1 and 0.2 m/s (scripted device, lockstep); fits f, B and a·v of the contact transient
/// back from the rendered force after the stop, and the stiffness felt at rest. Writes d3.csv,
/// d3.md, d3_transients.csv, d3_spectra.csv, d3.png and summary.json; returns 0 if every check
/// passes (f within 5 %, B within 25 %, a·v within 15 %, stiffness at rest within 1 %).
int RunD3(const std::filesystem::path& out, bool quiet);
/// D3's gnuplot figure from the CSVs in `out`.
void PlotD3(const std::filesystem::path& out, bool quiet);

// Chapter 3 (method proxy-6dof).

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
