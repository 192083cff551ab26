// SPDX-License-Identifier: Apache-2.0
// Perturbation simulations on the global world: accelerance A and bias b of neighbors (thesis
// §4.2.2, eq. 4.3–4.10).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/world/world.h"

namespace mrh::world::internal {
class IslandSolve;
}

namespace mrh::world {

/// 6×3 accelerance: COM acceleration [linear; angular] per unit force.
using Mat63 = Eigen::Matrix<double, 6, 3>;

/// How a perturbation run advances the world.
enum class PerturbationPath {
  /// mj_forwardSkip from the velocity stage on a forwarded base state whenever that reproduces a
  /// full step (Euler integrator, no joint damping, every listed body free or slide-jointed to a
  /// static parent); otherwise kFullStep. About 35–45 % of a full step per run.
  kAuto,
  /// A full World::Step and Restore per run: always exact, the reference for kAuto.
  kFullStep,
};

/// Where the constraint solver of a test-force run starts (its warm start).
enum class TestRunWarmStart {
  /// The zero-force run's solution. A test force changes that solution only around the pushed
  /// body, so the solver starts next to its answer and stops after a few iterations instead of
  /// redoing the whole world's solve. The result differs from kSaved by the solver's tolerance.
  kZeroForceSolution,
  /// The saved state's warm start, as a real step from that state would use: every run is
  /// exactly the step the world would take with that force (the reference for the above).
  kSaved,
};

/// How a Perturber runs its test-force runs.
struct PerturberSettings {
  PerturbationPath path = PerturbationPath::kAuto;
  /// Measure(): when forward skipping, solve each test-force run exactly on the measured body's
  /// constraint island (the bodies linked to it by constraint rows) instead of running MuJoCo's
  /// solver over the whole world. A run falls back to MuJoCo where the island has more than
  /// max_island_dofs dofs or rows other than equality, limit and frictionless or pyramidal
  /// contact, or its active set does not settle. The result is the exact minimizer of MuJoCo's
  /// constraint problem, which MuJoCo's iterative solver approaches within its tolerance.
  bool island_solve = true;
  /// Largest island solved exactly (dense 6n×6n Cholesky per run): 20 free bodies.
  int max_island_dofs = 120;
  /// Warm start of test-force runs done by MuJoCo's solver.
  TestRunWarmStart warm_start = TestRunWarmStart::kZeroForceSolution;
  /// Override of the model's solver tolerance (opt.tolerance) and iteration limit
  /// (opt.iterations) for every run, zero-force included; 0: the model's. A tight tolerance
  /// gives converged reference measurements.
  double solver_tolerance = 0.0;
  int solver_iterations = 0;
};

/// Dynamic intermediate representation of one body over one step (eq. 4.2): u̇ = A f + b, where u
/// is the COM twist [v; ω] in the world frame and f acts at the point used for the test forces.
struct DynamicIr {
  /// Accelerance: m/s² per N (rows 0–2) and rad/s² per N (rows 3–5), world frame (eq. 4.10).
  Mat63 A = Mat63::Zero();
  /// Bias acceleration without user force [m/s²; rad/s²], world frame.
  Vec6 b = Vec6::Zero();
};

/// The response of another body to the test forces on a measured one: its COM acceleration per
/// unit force on the measured body (a cross accelerance), for bodies in the same contact or joint
/// group.
struct GroupResponse {
  int body = -1;
  Mat63 A = Mat63::Zero();  ///< [m/s²; rad/s²] per N at the measured body's test point, world
};

/// What a Perturber did since construction.
struct PerturberCounters {
  std::int64_t begins = 0;           ///< Begin() calls
  std::int64_t zero_force_runs = 0;  ///< ZeroForceRun() calls
  std::int64_t force_runs = 0;       ///< ForceRun() calls (3 per Measure())
  /// runs (of both kinds) on the forward-skipped base: mj_forwardSkip, or the island solve
  std::int64_t forward_skip_runs = 0;
  std::int64_t full_step_runs = 0;  ///< runs (of both kinds) done with a full step
  std::int64_t run_ns = 0;          ///< wall time inside the runs (ns), for cost measurements
  /// MuJoCo constraint-solver iterations (mjData::solver_iter) of the zero-force runs and of the
  /// test-force runs, summed, and the most one test-force run used: the runs' cost in units of
  /// the global step's solve, independent of wall-clock noise.
  std::int64_t zero_force_solver_iterations = 0;
  std::int64_t force_run_solver_iterations = 0;
  int max_force_run_solver_iterations = 0;
  /// Test-force runs solved on the measured body's island (counted in forward_skip_runs too;
  /// they use no MuJoCo solver iterations), islands MuJoCo had to solve instead, the largest
  /// island solved (dofs) and the active-set iterations of the island solves.
  std::int64_t island_runs = 0;
  std::int64_t island_fallbacks = 0;
  int max_island_dofs = 0;
  std::int64_t island_iterations = 0;
  /// Group bodies left out of group() because forward skipping cannot read their velocity
  /// exactly (not free or slide-jointed to a static parent).
  std::int64_t group_bodies_unread = 0;
};

/// The three test forces of eq. 4.5–4.7 as columns: f1, |f1|·unit(e1 + e2) and |f1|·unit(e1 + e3)
/// (eq. 4.6 corrected: the thesis prints it as a copy of eq. 4.5, which would make the force
/// matrix singular), with e1 = unit(f1), e2 = unit(x̂ − (x̂·e1)e1) (ŷ instead when x̂
/// is nearly parallel to e1) and e3 = e1 × e2, so |det| = |f1|³/2. @pre f1 finite, |f1| > 0.
/// Not RT-safe (physics thread).
Mat3 TestForces(const Vec3& f1);

/// Key of a contact between two geoms, independent of their order. Not RT-safe.
std::uint64_t ContactKey(int geom_a, int geom_b);

/// Perturbation simulations (thesis §4.2.2) on a World: save the state, run one step without and
/// with test forces on selected bodies, read their COM twists, and restore the state exactly, so
/// that the next World::Step is bit-identical to one without the runs. Buffers are allocated at
/// construction and in the first Begin() for a given body count. Physics thread only; not
/// RT-safe.
///
///   perturber.Begin(bodies);           // save
///   perturber.ZeroForceRun();          // u_0 for every listed body (one run shared by all)
///   DynamicIr ir = perturber.Measure(i, f_user, p_W);  // 3 runs on bodies[i]
///   perturber.End();                   // restore
class Perturber {
 public:
  /// @param world the world to perturb; must outlive the perturber.
  /// @throws mrh::InvalidArgument if a count or tolerance in `settings` is negative.
  explicit Perturber(World* world, const PerturberSettings& settings = {});
  /// The default settings with another path.
  Perturber(World* world, PerturbationPath path);
  ~Perturber();
  Perturber(Perturber&&) noexcept;
  Perturber& operator=(Perturber&&) noexcept;

  /// Saves the state, lists the bodies whose velocities the runs read and records their current
  /// COM twists (u_(i) of eq. 4.3). With forward skipping this also does the forward pass of the
  /// zero-force run (the base the test-force runs start from). @pre no Begin() is open; every
  /// body is dynamic (has degrees of freedom).
  void Begin(std::span<const int> bodies);

  /// The zero-force run (eq. 4.3 with f = 0, thesis §4.2.2): one step without test force;
  /// afterwards zero_force_velocity(i) holds u_0 of bodies[i]. The state the world had at Begin()
  /// is not changed. @pre Begin() is open.
  void ZeroForceRun();

  /// One step from the saved state with force f_W (N, world) at p_W (m, world) on bodies[index];
  /// returns that body's COM twist after the step. @pre ZeroForceRun() was called.
  Twist ForceRun(std::size_t index, const Vec3& f_W, const Vec3& p_W);

  /// A and b of bodies[index] for a force at p_W (eq. 4.8–4.10, corrected): three ForceRun()s
  /// with TestForces(f1). @pre ZeroForceRun() was called; f1 finite, |f1| > 0.
  DynamicIr Measure(std::size_t index, const Vec3& f1, const Vec3& p_W);

  /// The bodies the last Measure()'s test forces moved besides the measured one (its contact or
  /// joint group), with their accelerances; readable until the next Measure().
  std::span<const GroupResponse> group() const { return group_; }

  /// Restores the saved state exactly (and the solver statistics of the step before Begin()).
  /// @pre Begin() is open.
  void End();

  /// COM twist of bodies[index] in the saved state (readable until the next Begin()).
  const Twist& start_velocity(std::size_t index) const;
  /// COM twist of bodies[index] after the zero-force run (readable until the next Begin()).
  const Twist& zero_force_velocity(std::size_t index) const;
  /// Geom pairs in contact at the saved state (MuJoCo contacts of the zero-force run), as sorted
  /// ContactKey()s; readable until the next Begin(). @pre ZeroForceRun() was called.
  std::span<const std::uint64_t> base_contacts() const;

  /// Right after a World::Step (before any state query): the COM twist change (world) that the
  /// step's contacts touching `body` whose geom pair is not in `known` (sorted ContactKey()s)
  /// gave it, M_B⁻¹ J_Bᵀ f Δt over the body's own degrees of freedom. This is the velocity jump
  /// of eq. 4.18 realized from the constraints that are new since A was measured (the thesis
  /// leaves f_n's computation open; this is one of two realizations, see CorrectionModel). Zero
  /// for a body without degrees of freedom. Needs no Begin().
  Twist NewContactVelocityChange(int body, std::span<const std::uint64_t> known);

  /// True when the open Begin() runs with mj_forwardSkip (see PerturbationPath::kAuto).
  bool forward_skip() const { return forward_skip_; }

  std::size_t num_bodies() const { return bodies_.size(); }

  const PerturberCounters& counters() const { return counters_; }

 private:
  void SetUpForwardSkip();
  const double* TestWarmStart() const;
  void CountTestIterations();
  void RecordBaseContacts();
  Twist Run(std::size_t index, const Vec3& f_W, const Vec3& p_W, int slot);
  Twist RunForwardSkip(std::size_t index, const Vec3& f_W, const Vec3& p_W, int slot);
  Twist RunFullStep(std::size_t index, const Vec3& f_W, const Vec3& p_W, int slot);
  bool RunIsland(std::size_t index, const Vec3& f_W, const Vec3& p_W, int slot, Twist* out);
  void CaptureFullStep(std::vector<double>* qvel, std::vector<Twist>* twists);
  void CollectGroup(int measured, const Mat3& F_inverse);

  World* world_;
  PerturberSettings settings_;
  // mjData::solver_niter and nisland at Begin(): the real step's (World::solver_iterations()).
  std::array<int, 20> saved_solver_iter_{};
  int saved_nisland_ = 0;
  bool model_allows_skip_ = false;  // Euler integrator and no joint damping
  Snapshot snapshot_;
  std::vector<int> bodies_;
  std::vector<Twist> start_;
  std::vector<Twist> zero_;
  std::vector<double> warmstart_;      // qacc_warmstart of the saved state
  std::vector<double> zero_solution_;  // qacc of the zero-force run (TestRunWarmStart)
  std::vector<double> zero_smooth_;    // qacc_smooth of the forward-skipped zero-force run
  std::vector<std::uint64_t> base_contacts_;
  std::vector<double> jacp_, jacr_;  // 3 × nv Jacobian scratch
  // Group responses: per dof, qacc (forward skipping) or qvel (full steps) of the zero-force run
  // and of the three test-force runs of a Measure(); per body, COM twists (full steps only).
  std::vector<double> zero_q_;
  std::array<std::vector<double>, 3> run_q_;
  std::vector<Twist> zero_twists_;
  std::array<std::vector<Twist>, 3> run_twists_;
  std::vector<GroupResponse> group_;
  std::unique_ptr<internal::IslandSolve> island_;
  bool island_ready_ = false;  // island_ holds the body of the current Measure()
  bool open_ = false;
  bool zero_done_ = false;
  bool forward_skip_ = false;
  double dt_ = 0.0;
  PerturberCounters counters_;
};

}  // namespace mrh::world
