// SPDX-License-Identifier: Apache-2.0
// Perturbation simulations over MuJoCo: minimal state copy and mj_forwardSkip from the
// velocity stage (DEPENDENCIES.md), with a full step as the exact fallback.
#include "mrh/world/perturbation.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <string>

#include "mrh/core/assert.h"
#include "mrh/core/error.h"
#include "world/island_solve_impl.h"
#include "world/perturbation_kinematics.h"
#include "world/world_impl.h"

namespace mrh::world {

static_assert(mjNISLAND == 20, "Perturber::saved_solver_iter_ holds mjData::solver_niter");

namespace {

using internal::IsFreeBody;
using internal::IsSlideBody;
using internal::ToVec3;
using internal::TwistAfterEuler;

std::int64_t NowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Sets the settings' solver tolerance and iteration limit on the model for one run (the model is
// const otherwise) and puts the model's own back.
class SolverOverride {
 public:
  SolverOverride(mjModel* m, const PerturberSettings& settings)
      : m_(m), tolerance_(m->opt.tolerance), iterations_(m->opt.iterations) {
    if (settings.solver_tolerance > 0.0) m->opt.tolerance = settings.solver_tolerance;
    if (settings.solver_iterations > 0) m->opt.iterations = settings.solver_iterations;
  }

  ~SolverOverride() {
    m_->opt.tolerance = tolerance_;
    m_->opt.iterations = iterations_;
  }

  SolverOverride(const SolverOverride&) = delete;
  SolverOverride& operator=(const SolverOverride&) = delete;

 private:
  mjModel* m_;
  mjtNum tolerance_;
  int iterations_;
};

}  // namespace

Perturber::Perturber(World* world, PerturbationPath path)
    : Perturber(world, PerturberSettings{.path = path}) {}

Perturber::Perturber(World* world, const PerturberSettings& settings)
    : world_(world), settings_(settings) {
  MRH_DEMAND(world_ != nullptr);
  if (settings_.max_island_dofs < 0 || settings_.solver_iterations < 0 ||
      !(settings_.solver_tolerance >= 0.0)) {
    throw InvalidArgument(
        "Perturber: max_island_dofs = " + std::to_string(settings_.max_island_dofs) +
        ", solver_iterations = " + std::to_string(settings_.solver_iterations) +
        ", solver_tolerance = " + std::to_string(settings_.solver_tolerance) +
        "; expected each >= 0 (0: the model's own solver settings)");
  }
  island_ = std::make_unique<internal::IslandSolve>();
  const mjModel& m = *world_->impl_->model;
  // mj_Euler integrates damping implicitly, which changes qacc after the forward pass.
  model_allows_skip_ = m.opt.integrator == mjINT_EULER;
  for (int i = 0; i < m.nv; ++i) {
    if (m.dof_damping[i] > 0.0) model_allows_skip_ = false;
  }
  snapshot_ = world_->MakeSnapshot();
  warmstart_.assign(static_cast<std::size_t>(m.nv), 0.0);
  zero_solution_.assign(static_cast<std::size_t>(m.nv), 0.0);
  zero_smooth_.assign(static_cast<std::size_t>(m.nv), 0.0);
  jacp_.assign(3 * static_cast<std::size_t>(m.nv), 0.0);
  jacr_.assign(3 * static_cast<std::size_t>(m.nv), 0.0);
  const auto nv = static_cast<std::size_t>(m.nv);
  const auto nbody = static_cast<std::size_t>(m.nbody);
  zero_q_.assign(nv, 0.0);
  zero_twists_.assign(nbody, Twist{});
  for (std::size_t k = 0; k < 3; ++k) {
    run_q_[k].assign(nv, 0.0);
    run_twists_[k].assign(nbody, Twist{});
  }
  group_.reserve(nbody);
  const auto capacity = static_cast<std::size_t>(m.nbody);
  bodies_.reserve(capacity);
  start_.reserve(capacity);
  zero_.reserve(capacity);
}

Perturber::~Perturber() = default;
Perturber::Perturber(Perturber&&) noexcept = default;
Perturber& Perturber::operator=(Perturber&&) noexcept = default;

void Perturber::Begin(std::span<const int> bodies) {
  MRH_DEMAND(!open_);
  const mjModel& m = *world_->impl_->model;
  bodies_.assign(bodies.begin(), bodies.end());
  forward_skip_ = settings_.path == PerturbationPath::kAuto && model_allows_skip_;
  for (int body : bodies_) {
    MRH_DEMAND(body > 0 && body < m.nbody && m.body_dofnum[body] > 0);
    if (!IsFreeBody(m, body) && !IsSlideBody(m, body)) forward_skip_ = false;
  }
  world_->Save(&snapshot_);
  std::copy_n(world_->impl_->data->solver_niter, mjNISLAND, saved_solver_iter_.begin());
  saved_nisland_ = world_->impl_->data->nisland;
  dt_ = m.opt.timestep;
  start_.resize(bodies_.size());
  zero_.resize(bodies_.size());
  open_ = true;
  zero_done_ = false;
  ++counters_.begins;
  if (forward_skip_) {
    const std::int64_t t0 = NowNs();
    SetUpForwardSkip();
    counters_.run_ns += NowNs() - t0;
    return;
  }
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    start_[i] = world_->body_state(bodies_[i]).V_WCm;
  }
}

// The zero-force run is the forward pass of the step itself, done here. Its position and velocity
// stages (kinematics, collision, constraint Jacobians, bias forces) do not depend on applied
// forces, so every test-force run keeps them and redoes only actuation, acceleration and the
// constraint solve.
void Perturber::SetUpForwardSkip() {
  World::Impl& w = *world_->impl_;
  const mjModel* m = w.model.get();
  mjData* d = w.data.get();
  std::copy_n(d->qacc_warmstart, m->nv, warmstart_.data());
  {
    const SolverOverride solver(w.model.get(), settings_);
    const internal::MujocoScope scope(w.origin);
    mj_forwardSkip(m, d, mjSTAGE_NONE, 1);
  }
  std::copy_n(d->qacc_smooth, m->nv, zero_smooth_.data());
  w.kinematics_stale = false;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    start_[i] = TwistAfterEuler(*m, *d, bodies_[i], 0.0, d->qacc);
    zero_[i] = TwistAfterEuler(*m, *d, bodies_[i], dt_, d->qacc);
  }
  std::copy_n(d->qacc, m->nv, zero_q_.data());
  std::copy_n(d->qacc, m->nv, zero_solution_.data());
}

const double* Perturber::TestWarmStart() const {
  return settings_.warm_start == TestRunWarmStart::kZeroForceSolution ? zero_solution_.data()
                                                                      : warmstart_.data();
}

void Perturber::CountTestIterations() {
  const int used = internal::SolverIterations(*world_->impl_->data);
  counters_.force_run_solver_iterations += used;
  counters_.max_force_run_solver_iterations =
      std::max(counters_.max_force_run_solver_iterations, used);
}

void Perturber::ZeroForceRun() {
  MRH_DEMAND(open_);
  const std::int64_t t0 = NowNs();
  if (forward_skip_) {
    // Begin() already did this run's forward pass; its results are still in the data.
    RecordBaseContacts();
    counters_.zero_force_solver_iterations += internal::SolverIterations(*world_->impl_->data);
    ++counters_.forward_skip_runs;
  } else {
    {
      const SolverOverride solver(world_->impl_->model.get(), settings_);
      world_->Step();
    }
    RecordBaseContacts();  // the step's forward pass ran at the saved state
    const mjData& d = *world_->impl_->data;
    counters_.zero_force_solver_iterations += internal::SolverIterations(d);
    std::copy_n(d.qacc, world_->impl_->model->nv, zero_solution_.data());
    CaptureFullStep(&zero_q_, &zero_twists_);
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      zero_[i] = zero_twists_[static_cast<std::size_t>(bodies_[i])];
    }
    world_->Restore(snapshot_);
    ++counters_.full_step_runs;
  }
  zero_done_ = true;
  ++counters_.zero_force_runs;
  counters_.run_ns += NowNs() - t0;
}

Twist Perturber::ForceRun(std::size_t index, const Vec3& f_W, const Vec3& p_W) {
  return Run(index, f_W, p_W, -1);
}

Twist Perturber::Run(std::size_t index, const Vec3& f_W, const Vec3& p_W, int slot) {
  MRH_DEMAND(open_ && zero_done_ && index < bodies_.size());
  const std::int64_t t0 = NowNs();
  Twist result;
  if (island_ready_ && slot >= 0 && RunIsland(index, f_W, p_W, slot, &result)) {
    // solved on the island
  } else {
    if (island_ready_) ++counters_.island_fallbacks;
    const SolverOverride solver(world_->impl_->model.get(), settings_);
    result =
        forward_skip_ ? RunForwardSkip(index, f_W, p_W, slot) : RunFullStep(index, f_W, p_W, slot);
  }
  ++counters_.force_runs;
  counters_.run_ns += NowNs() - t0;
  return result;
}

Twist Perturber::RunForwardSkip(std::size_t index, const Vec3& f_W, const Vec3& p_W, int slot) {
  World::Impl& w = *world_->impl_;
  const mjModel* m = w.model.get();
  mjData* d = w.data.get();
  const int body = bodies_[index];
  // The solver's warm start (TestRunWarmStart), the same as RunFullStep's.
  std::copy_n(TestWarmStart(), m->nv, d->qacc_warmstart);
  mjtNum* xfrc = d->xfrc_applied + 6 * body;
  std::array<mjtNum, 6> saved{};
  std::copy_n(xfrc, 6, saved.data());
  // xfrc_applied takes the torque about the COM (xipos, current from the base forward pass).
  const Vec3 tau = (p_W - ToVec3(d->xipos + 3 * body)).cross(f_W);
  for (int i = 0; i < 3; ++i) {
    xfrc[i] += f_W[i];
    xfrc[3 + i] += tau[i];
  }
  {
    const internal::MujocoScope scope(world_->impl_->origin);
    mj_forwardSkip(m, d, mjSTAGE_VEL, 1);
  }
  CountTestIterations();
  std::copy_n(saved.data(), 6, xfrc);
  if (slot >= 0) std::copy_n(d->qacc, m->nv, run_q_[static_cast<std::size_t>(slot)].data());
  ++counters_.forward_skip_runs;
  return TwistAfterEuler(*m, *d, body, dt_, d->qacc);
}

// The exact island solution (PerturberSettings::island_solve) in place of mj_forwardSkip.
bool Perturber::RunIsland(std::size_t index, const Vec3& f_W, const Vec3& p_W, int slot,
                          Twist* out) {
  const World::Impl& w = *world_->impl_;
  std::vector<double>& qacc = run_q_[static_cast<std::size_t>(slot)];
  const bool solved =
      island_->Solve(*w.model, w.data.get(), f_W.data(), p_W.data(), zero_q_.data(), qacc.data());
  counters_.island_iterations += island_->iterations();
  if (!solved) return false;
  ++counters_.island_runs;
  ++counters_.forward_skip_runs;
  *out = TwistAfterEuler(*w.model, *w.data, bodies_[index], dt_, qacc.data());
  return true;
}

Twist Perturber::RunFullStep(std::size_t index, const Vec3& f_W, const Vec3& p_W, int slot) {
  const int body = bodies_[index];
  world_->AddForceAtPoint(body, f_W, p_W);
  std::copy_n(TestWarmStart(), world_->impl_->model->nv, world_->impl_->data->qacc_warmstart);
  world_->Step();
  CountTestIterations();
  const Twist result = world_->body_state(body).V_WCm;
  if (slot >= 0) {
    const auto k = static_cast<std::size_t>(slot);
    CaptureFullStep(&run_q_[k], &run_twists_[k]);
  }
  world_->Restore(snapshot_);
  ++counters_.full_step_runs;
  return result;
}

// After a full-step run, before restoring: generalized velocities, and the COM twists of every
// body with degrees of freedom (which ones responded is known only after all three runs).
void Perturber::CaptureFullStep(std::vector<double>* qvel, std::vector<Twist>* twists) {
  const World::Impl& w = *world_->impl_;
  std::copy_n(w.data->qvel, w.model->nv, qvel->data());
  for (int b = 1; b < w.model->nbody; ++b) {
    if (w.model->body_dofnum[b] > 0)
      (*twists)[static_cast<std::size_t>(b)] = world_->body_state(b).V_WCm;
  }
}

void Perturber::End() {
  MRH_DEMAND(open_);
  world_->Restore(snapshot_);
  // World::solver_iterations(): the step's
  std::copy_n(saved_solver_iter_.begin(), mjNISLAND, world_->impl_->data->solver_niter);
  world_->impl_->data->nisland = saved_nisland_;
  open_ = false;  // the velocities stay readable until the next Begin()
}

const Twist& Perturber::start_velocity(std::size_t index) const {
  MRH_DEMAND(index < start_.size());
  return start_[index];
}

const Twist& Perturber::zero_force_velocity(std::size_t index) const {
  MRH_DEMAND(zero_done_ && index < zero_.size());
  return zero_[index];
}

}  // namespace mrh::world
