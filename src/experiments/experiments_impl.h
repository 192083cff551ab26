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

#include "experiments_chapter3.h"
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

}  // namespace mrh::experiments::internal
