// SPDX-License-Identifier: Apache-2.0
// 6-DOF proxy rendering: one tick — previous proxy, solve, wrench and per-pair reactions.
// The rows are built in proxy_rows.cc, the settings validated in proxy_renderer_settings.cc.
#include "mrh/render/proxy_renderer.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mrh::render {
namespace {

const ProxyRendererSettings& Validated(const ProxyRendererSettings& settings) {
  settings.Validate();
  return settings;
}

}  // namespace

ProxyRenderer::ProxyRenderer(const ProxyRendererSettings& settings)
    : settings_(Validated(settings)),
      pgs_(settings.solver == ProxySolverKind::kPgs ? settings.max_rows : 1),
      active_set_(settings.solver == ProxySolverKind::kActiveSet ? settings.max_rows : 1),
      split_(settings.max_rows, ir::kMaxGeometricPairs) {
  // Symmetrize both ways so the row weights g_k see an exactly symmetric R_w⁻¹.
  const Mat3 given = settings_.torque_model == ProxyTorqueModel::kContact
                         ? Mat3((settings_.k_r / settings_.k_t) * Mat3::Identity())
                         : settings_.rotation_weight;
  const Mat3 weight = 0.5 * (given + given.transpose());
  const Mat3 inverse = weight.inverse();
  rotation_weight_inverse_ = 0.5 * (inverse + inverse.transpose());
  rows_.resize(settings_.max_rows);
  info_.resize(settings_.max_rows);
  ids_.resize(settings_.max_rows);
  previous_ids_.resize(settings_.max_rows);
  f_.resize(settings_.max_rows);
  previous_f_.resize(settings_.max_rows);
  split_row_.resize(split_.capacity());
}

void ProxyRenderer::Reset() noexcept {
  row_count_ = 0;
  previous_row_count_ = 0;
  memory_count_ = 0;
  has_previous_ = false;
  previous_X_WQ_ = Pose{};
  previous_dr_.setZero();
  previous_dtheta_.setZero();
  split_.Reset();
}

void ProxyRenderer::Tick(const TickIr& ir, const Pose& X_WP, double dt, ProxyOutput* out) noexcept {
  out->reactions.Clear();
  out->diagnostics = ProxyDiagnostics{};
  if (!InputIsFinite(ir, X_WP, dt)) return Fault(X_WP, out);

  // The last tick's ids and f become "previous" for the warm start.
  std::swap(ids_, previous_ids_);
  std::swap(f_, previous_f_);
  previous_row_count_ = row_count_;
  row_count_ = 0;

  CarryPreviousProxy(ir, X_WP);
  // The points are checked for finite data while the rows are built (one pass over them).
  if (!BuildRows(ir, X_WP, &out->diagnostics)) return Fault(X_WP, out);
  Solve(out);
  out->rows = std::span<const ProxyRow>(rows_.data(), row_count_);
  out->row_info = std::span<const ProxyRowInfo>(info_.data(), row_count_);
  out->f = std::span<const double>(f_.data(), row_count_);
  const bool thesis = settings_.torque_model == ProxyTorqueModel::kThesis;
  if (thesis) {
    // eq. 3.7–3.8: springs on the proxy offset, dampers on its finite difference. The first
    // tick after a start or reset has no previous offset: its difference would be the whole
    // offset (a pointer that starts inside an object would feel d·dr/dt on top of k·dr), so the
    // dampers start at rest.
    const Vec3& dr_before = has_previous_ ? previous_dr_ : out->dr;
    const Vec3& dtheta_before = has_previous_ ? previous_dtheta_ : out->dtheta;
    out->w_W.f = settings_.k_t * out->dr + settings_.d_t * (out->dr - dr_before) / dt;
    out->w_W.tau = settings_.k_r * out->dtheta + settings_.d_r * (out->dtheta - dtheta_before) / dt;
  } else {
    ComputeContactForces(ir, X_WP, dt, out);
  }
  const Quat q_WP = X_WP.q.normalized();
  out->X_WQ = Pose{X_WP.p + out->dr, (QuatFromRotationVector(out->dtheta) * q_WP).normalized()};
  if (!IsFinite(out->w_W) || !IsFinite(out->X_WQ)) return Fault(X_WP, out);
  if (thesis) ComputeReactions(ir, X_WP, dt, out);
  Remember(ir, *out);
}

// Thesis §3.2.4 step 5: the proxy offset (Δr, Δθ) and the multipliers f of this tick's rows.
void ProxyRenderer::Solve(ProxyOutput* out) noexcept {
  const std::span<const ProxyRow> rows(rows_.data(), row_count_);
  const std::span<double> f(f_.data(), row_count_);
  const ProxySolverSettings budget{SweepBudget(), settings_.tolerance};
  const ProxySolveResult solved =
      settings_.solver == ProxySolverKind::kPgs
          ? pgs_.Solve(rows, rotation_weight_inverse_, budget, f, &out->dr, &out->dtheta)
          : active_set_.Solve(rows, rotation_weight_inverse_, budget, f, &out->dr, &out->dtheta);
  ProxyDiagnostics& diag = out->diagnostics;
  diag.rows = static_cast<int>(row_count_);
  diag.iterations = solved.iterations;
  diag.converged = solved.converged;
  diag.max_change = solved.max_change;
  if (!solved.converged) diag.status |= kProxyStatusNotConverged;
}

int ProxyRenderer::SweepBudget() const noexcept {
  if (settings_.solver != ProxySolverKind::kPgs || settings_.max_row_updates == 0 ||
      row_count_ == 0) {
    return settings_.max_iterations;
  }
  const std::size_t sweeps = std::max<std::size_t>(1, settings_.max_row_updates / row_count_);
  return static_cast<int>(std::min(sweeps, static_cast<std::size_t>(settings_.max_iterations)));
}

// The pose, dt and the pairs; the points are checked by BuildRows.
bool ProxyRenderer::InputIsFinite(const TickIr& ir, const Pose& X_WP, double dt) const noexcept {
  if (!IsFinite(X_WP) || !(X_WP.q.norm() > 0.0) || !std::isfinite(dt) || !(dt > 0.0)) {
    return false;
  }
  for (const TickPair& pair : ir.pairs) {
    if (!IsFinite(pair.X_WB) || !IsFinite(pair.p_WCm) || !IsFinite(pair.n_W) ||
        !IsFinite(pair.c_W)) {
      return false;
    }
  }
  return true;
}

// Thesis §3.2.3 (eq. 3.9) on moving objects: each pair's "previous proxy" is last tick's proxy
// carried along by its object's motion since then, or the current pointer on the contact's first
// tick (sticking; the thesis is silent on both, and Springhead does the same).
void ProxyRenderer::CarryPreviousProxy(const TickIr& ir, const Pose& X_WP) noexcept {
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
    const TickPair& pair = ir.pairs[i];
    gains_[i] = ir::GainsOf(pair.material, {settings_.k_t, settings_.d_t, settings_.mu});
    const PairMemory* memory = nullptr;
    // Pairs usually keep their order between ticks: try the same slot first.
    if (i < memory_count_ && memory_[i].key == pair.key) memory = &memory_[i];
    for (std::size_t o = 0; memory == nullptr && o < memory_count_; ++o) {
      if (memory_[o].key == pair.key) memory = &memory_[o];
    }
    previous_dr_pair_[i] = memory != nullptr ? memory->dr_pair : Vec3::Zero();
    previous_dtheta_pair_[i] = memory != nullptr ? memory->dtheta_pair : Vec3::Zero();
    first_tick_[i] = !(has_previous_ && memory != nullptr && memory->in_contact);
    const Pose carried =
        first_tick_[i] ? X_WP : pair.X_WB * (memory->X_WB.Inverse() * previous_X_WQ_);
    // As a matrix: every friction row of the pair poses a point with it.
    carried_R_WQ_[i] = carried.q.normalized().toRotationMatrix();
    carried_p_WQ_[i] = carried.p;
  }
}

// The reaction on the objects (thesis §3.5 only says the haptic side computes it), made
// consistent with what the user feels: pair i's rows contribute
// Δr_i = Σ f_k a_k and Δθ_i = Σ f_k R_w⁻¹(r_k × a_k) to the proxy offset (Σ_i Δr_i = Δr,
// Σ_i Δθ_i = Δθ), so it pushes the pointer with the spring–damper share
// F_i = k_t Δr_i + d_t (Δr_i − Δr_i,prev)/dt and τ_i = k_r Δθ_i + d_r (Δθ_i − Δθ_i,prev)/dt
// about the pointer origin; DistributeReactions hands −(F_i, τ_i) to the objects. Summed over
// the pairs this is exactly minus the rendered wrench (action = reaction). A per-row
// moment Σ (p_k − c) × k_t f_k a_k would instead give the objects k_t R_w Δθ, which for the
// thesis weights (R_w = 3.33–8420 m², k_t ≈ k_r) is 3–8000× the torque the user feels.
void ProxyRenderer::ComputeReactions(const TickIr& ir, const Pose& X_WP, double dt,
                                     ProxyOutput* out) noexcept {
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
    dr_pair_[i].setZero();
    dtheta_pair_[i].setZero();
  }
  const auto add = [&](std::size_t k) noexcept {
    const auto i = static_cast<std::size_t>(info_[k].pair);
    dr_pair_[i] += f_[k] * rows_[k].a;
    dtheta_pair_[i] += f_[k] * (rotation_weight_inverse_ * rows_[k].r.cross(rows_[k].a));
  };
  if (settings_.solver == ProxySolverKind::kActiveSet) {
    // Only the <= 6 active rows can have f != 0.
    for (const int k : active_set_.active_rows()) {
      if (f_[static_cast<std::size_t>(k)] != 0.0) add(static_cast<std::size_t>(k));
    }
  } else {
    for (std::size_t k = 0; k < row_count_; ++k) {
      if (f_[k] != 0.0) add(k);
    }
  }
  DistributeReactions(ir, X_WP, dt, out);
}

// One touched pair takes the whole wrench: −(F_i, τ_i) moved to its COM, with its own damper
// difference. Several: SplitAcrossPairs (proxy_reaction_split.cc). Either way each non-static
// touched pair's object receives −F_i and the moment −(M_i + (x_p − p_Cm) × F_i) about its COM.
void ProxyRenderer::DistributeReactions(const TickIr& ir, const Pose& X_WP, double dt,
                                        ProxyOutput* out) noexcept {
  std::size_t touched = 0;
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) touched += pair_rows_[i] > 0 ? 1 : 0;
  if (touched > 1) {
    SplitAcrossPairs(ir, touched, out);
  } else {
    for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
      force_pair_[i] =
          settings_.k_t * dr_pair_[i] + settings_.d_t * (dr_pair_[i] - previous_dr_pair_[i]) / dt;
      torque_pair_[i] = settings_.k_r * dtheta_pair_[i] +
                        settings_.d_r * (dtheta_pair_[i] - previous_dtheta_pair_[i]) / dt;
    }
  }
  PushReactions(ir, X_WP, out);
}

// Pair i pushes the pointer with F_i and M_i (about the pointer origin): its object, unless
// static, receives −F_i and the moment −(M_i + (x_p − p_Cm) × F_i) about its COM.
void ProxyRenderer::PushReactions(const TickIr& ir, const Pose& X_WP,
                                  ProxyOutput* out) const noexcept {
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
    const TickPair& pair = ir.pairs[i];
    Wrench w_W;  // on the object, torque about its COM
    if (!pair.is_static && pair_rows_[i] > 0) {
      w_W.f = -force_pair_[i];
      w_W.tau = -(torque_pair_[i] + (X_WP.p - pair.p_WCm).cross(force_pair_[i]));
    }
    (void)out->reactions.PushBack(ProxyPairReaction{pair.key, pair.body, pair.is_static, w_W});
  }
}

void ProxyRenderer::Remember(const TickIr& ir, const ProxyOutput& out) noexcept {
  memory_count_ = ir.pairs.size();
  for (std::size_t i = 0; i < memory_count_; ++i) {
    const TickPair& pair = ir.pairs[i];
    memory_[i] = PairMemory{pair.key, pair.X_WB, pair_rows_[i] > 0, dr_pair_[i], dtheta_pair_[i]};
  }
  previous_total_load_ = 0.0;
  for (std::size_t i = 0; i < memory_count_; ++i) previous_total_load_ += normal_load_[i];
  has_previous_ = true;
  previous_X_WQ_ = out.X_WQ;
  previous_dr_ = out.dr;
  previous_dtheta_ = out.dtheta;
}

void ProxyRenderer::Fault(const Pose& X_WP, ProxyOutput* out) noexcept {
  Reset();
  out->w_W = Wrench{};
  out->X_WQ = IsFinite(X_WP) ? X_WP : Pose{};
  out->dr.setZero();
  out->dtheta.setZero();
  out->rows = {};
  out->row_info = {};
  out->f = {};
  out->reactions.Clear();
  out->diagnostics = ProxyDiagnostics{};
  out->diagnostics.status = kProxyStatusBadInput;
}

}  // namespace mrh::render
