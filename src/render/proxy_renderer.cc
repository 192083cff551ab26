// SPDX-License-Identifier: Apache-2.0
// 6-DOF proxy rendering: rows from the tick IR, friction cones, PGS, wrench and reactions.
#include "mrh/render/proxy_renderer.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "mrh/core/error.h"
#include "mrh/core/validate.h"

namespace mrh::render {
namespace {

// A tangential offset |s| below this is rounding of metre-scale poses (~1e-16 m), not motion:
// no friction row (SPEC §3.7, "|s| about 0").
constexpr double kMinSlip = 1e-12;
// R_w counts as symmetric when |R − Rᵀ| is within this fraction of its largest entry.
constexpr double kSymmetryTolerance = 1e-12;

std::string Text(double value) {
  return FormatNumber(value);
}

void RequireNonNegative(double value, const char* field, const char* unit) {
  mrh::RequireNonNegative(value, std::string("ProxyRendererSettings.") + field, unit);
}

bool IsSymmetricPositiveDefinite(const Mat3& m) {
  if (!m.allFinite()) return false;
  const double scale = m.cwiseAbs().maxCoeff();
  if ((m - m.transpose()).cwiseAbs().maxCoeff() > kSymmetryTolerance * scale) return false;
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(m, Eigen::EigenvaluesOnly);
  return eigen.eigenvalues().minCoeff() > 0.0;
}

std::string Text(const Mat3& m) {
  std::string text = "[";
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) text += (c > 0 ? " " : r > 0 ? "; " : "") + Text(m(r, c));
  }
  return text + "]";
}

const ProxyRendererSettings& Validated(const ProxyRendererSettings& settings) {
  settings.Validate();
  return settings;
}

// Warm-start identity of a row: pair, point index in the tick IR and row kind. Within one
// snapshot the points keep their indices, so a persisting row finds its f; when a new snapshot
// re-derives the points (qhull vertices of the new pose), rows of the same index start from the
// old f, a start like any other (the solvers accept any start).
std::uint64_t RowIdOf(std::uint64_t key, std::size_t point_index, bool friction) noexcept {
  return (key * 0x9e3779b97f4a7c15ULL) ^ (static_cast<std::uint64_t>(point_index) << 1) ^
         (friction ? 1u : 0u);
}

}  // namespace

void ProxyRendererSettings::Validate() const {
  RequireNonNegative(k_t, "k_t", "N/m");
  RequireNonNegative(d_t, "d_t", "N·s/m");
  RequireNonNegative(k_r, "k_r", "N·m/rad");
  RequireNonNegative(d_r, "d_r", "N·m·s/rad");
  RequireNonNegative(mu, "mu", "(friction coefficient)");
  RequireNonNegative(tolerance, "tolerance", "m");
  if (!IsSymmetricPositiveDefinite(rotation_weight)) {
    throw InvalidArgument("ProxyRendererSettings.rotation_weight = " + Text(rotation_weight) +
                          " m²; expected a finite symmetric positive definite matrix; use "
                          "RotationWeightFromInertia or a positive diagonal");
  }
  if (max_iterations < 1 || max_iterations > kMaxProxyIterations) {
    throw InvalidArgument(
        "ProxyRendererSettings.max_iterations = " + std::to_string(max_iterations) +
        "; expected 1.." + std::to_string(kMaxProxyIterations) + "; set a sweep budget (20–50)");
  }
  if (max_rows < 1 || max_rows > kMaxProxyRows) {
    throw InvalidArgument("ProxyRendererSettings.max_rows = " + std::to_string(max_rows) +
                          "; expected 1.." + std::to_string(kMaxProxyRows) +
                          "; set it to 2 × the contact points you expect (or leave the default)");
  }
}

Mat3 RotationWeightFromInertia(const Mat3& unit_mass_inertia, double scale) {
  if (!(std::isfinite(scale) && scale > 0.0)) {
    throw InvalidArgument("RotationWeightFromInertia: scale = " + Text(scale) +
                          "; expected finite and > 0; set rotation_weight_scale > 0");
  }
  if (!IsSymmetricPositiveDefinite(unit_mass_inertia)) {
    throw InvalidArgument(
        "RotationWeightFromInertia: unit_mass_inertia = " + Text(unit_mass_inertia) +
        " m²; expected a finite symmetric positive definite tensor; give the "
        "pointer's inertia for mass 1 kg");
  }
  return scale * unit_mass_inertia;
}

ProxyRenderer::ProxyRenderer(const ProxyRendererSettings& settings)
    : settings_(Validated(settings)),
      pgs_(settings.solver == ProxySolverKind::kPgs ? settings.max_rows : 1),
      active_set_(settings.solver == ProxySolverKind::kActiveSet ? settings.max_rows : 1) {
  // Symmetrize both ways so the row weights g_k see an exactly symmetric R_w⁻¹.
  const Mat3 weight = 0.5 * (settings_.rotation_weight + settings_.rotation_weight.transpose());
  const Mat3 inverse = weight.inverse();
  rotation_weight_inverse_ = 0.5 * (inverse + inverse.transpose());
  rows_.resize(settings_.max_rows);
  info_.resize(settings_.max_rows);
  ids_.resize(settings_.max_rows);
  previous_ids_.resize(settings_.max_rows);
  f_.resize(settings_.max_rows);
  previous_f_.resize(settings_.max_rows);
}

void ProxyRenderer::Reset() noexcept {
  row_count_ = 0;
  previous_row_count_ = 0;
  memory_count_ = 0;
  has_previous_ = false;
  previous_X_WQ_ = Pose{};
  previous_dr_.setZero();
  previous_dtheta_.setZero();
}

void ProxyRenderer::Tick(const TickIr& ir, const Pose& X_WP, double dt, ProxyOutput* out) noexcept {
  out->reactions.Clear();
  out->diagnostics = ProxyDiagnostics{};
  if (!InputIsFinite(ir, X_WP, dt)) return Fault(X_WP, out);
  ProxyDiagnostics& diag = out->diagnostics;

  // The last tick's ids and f become "previous" for the warm start.
  std::swap(ids_, previous_ids_);
  std::swap(f_, previous_f_);
  previous_row_count_ = row_count_;
  row_count_ = 0;

  CarryPreviousProxy(ir, X_WP);
  // The points are checked for finite data while the rows are built (one pass over them).
  if (!BuildRows(ir, X_WP, &diag)) return Fault(X_WP, out);
  const std::span<const ProxyRow> rows(rows_.data(), row_count_);
  const std::span<double> f(f_.data(), row_count_);
  const ProxySolverSettings budget{SweepBudget(), settings_.tolerance};
  const ProxySolveResult solved =
      settings_.solver == ProxySolverKind::kPgs
          ? pgs_.Solve(rows, rotation_weight_inverse_, budget, f, &out->dr, &out->dtheta)
          : active_set_.Solve(rows, rotation_weight_inverse_, budget, f, &out->dr, &out->dtheta);
  diag.rows = static_cast<int>(row_count_);
  diag.iterations = solved.iterations;
  diag.converged = solved.converged;
  diag.max_change = solved.max_change;
  if (!solved.converged) diag.status |= kProxyStatusNotConverged;

  // eq. 3.7–3.8: springs on the proxy offset, dampers on its finite difference. The first tick
  // after a start or reset has no previous offset: its difference would be the whole offset
  // (a pointer that starts inside an object would feel d·dr/dt on top of k·dr), so the dampers
  // start at rest.
  const Vec3& dr_before = has_previous_ ? previous_dr_ : out->dr;
  const Vec3& dtheta_before = has_previous_ ? previous_dtheta_ : out->dtheta;
  out->w_W.f = settings_.k_t * out->dr + settings_.d_t * (out->dr - dr_before) / dt;
  out->w_W.tau = settings_.k_r * out->dtheta + settings_.d_r * (out->dtheta - dtheta_before) / dt;
  const Quat q_WP = X_WP.q.normalized();
  out->X_WQ = Pose{X_WP.p + out->dr, (QuatFromRotationVector(out->dtheta) * q_WP).normalized()};
  if (!IsFinite(out->w_W) || !IsFinite(out->X_WQ)) return Fault(X_WP, out);

  out->rows = std::span<const ProxyRow>(rows_.data(), row_count_);
  out->row_info = std::span<const ProxyRowInfo>(info_.data(), row_count_);
  out->f = std::span<const double>(f_.data(), row_count_);
  ComputeReactions(ir, X_WP, dt, out);
  Remember(ir, *out);
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

// SPEC §3.7 with I6: each pair's "previous proxy" is last tick's proxy carried along by its
// object's motion since then, or the current pointer on the contact's first tick (sticking).
void ProxyRenderer::CarryPreviousProxy(const TickIr& ir, const Pose& X_WP) noexcept {
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
    const TickPair& pair = ir.pairs[i];
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

// SPEC §3.8 steps 2–4: a normal row (eq. 3.1) per penetrating point, then its friction row
// (eq. 3.9–3.10), each started from last tick's f if the same row existed (SPEC §3.5 / I7).
// One pass over the points, which also checks them: false if any value is not finite. This is
// the per-contact cost of a tick, so it is written as one loop over plain arrays.
bool ProxyRenderer::BuildRows(const TickIr& ir, const Pose& X_WP, ProxyDiagnostics* diag) noexcept {
  const std::size_t pair_count = ir.pairs.size();
  for (std::size_t i = 0; i < pair_count; ++i) pair_rows_[i] = 0;
  ProxyRow* const rows = rows_.data();
  ProxyRowInfo* const info = info_.data();
  RowId* const ids = ids_.data();
  double* const f = f_.data();
  const RowId* const previous_ids = previous_ids_.data();
  const double* const previous_f = previous_f_.data();
  const std::size_t capacity = rows_.size();
  const std::size_t previous_count = previous_row_count_;
  const double mu = settings_.mu;
  const Vec3 x_p = X_WP.p;
  std::size_t k = 0;
  int contacts = 0, sticking = 0, sliding = 0, warm = 0;
  bool full = false;
  // Appends row k with its warm start: last tick's f if the row in this slot had the same id.
  const auto push = [&](const Vec3& a, const Vec3& r, double rhs, ProxyRowKind kind, int point,
                        int pair, RowId id) noexcept {
    rows[k].a = a;
    rows[k].r = r;
    rows[k].rhs = rhs;
    info[k] = ProxyRowInfo{kind, point, pair};
    ids[k] = id;
    const bool same = k < previous_count && previous_ids[k] == id;
    f[k] = same ? previous_f[k] : 0.0;
    warm += same ? 1 : 0;
    ++k;
  };

  // The current pair's data, loaded when the pair index changes (points come grouped by pair).
  int current = -1;
  Vec3 n = Vec3::UnitZ(), c = Vec3::Zero(), p_WQ = Vec3::Zero();
  Mat3 R_WQ = Mat3::Identity();
  std::uint64_t pair_key = 0;
  bool with_friction = false;

  // A sum of values is finite unless one of them is not (or it overflows, at ~1e308 m), and
  // x − x is 0 for finite x and NaN otherwise: nan_if_bad is NaN iff some value is not finite.
  double nan_if_bad = 0.0;
  const std::size_t point_count = ir.points.size();
  for (std::size_t p = 0; p < point_count; ++p) {
    const TickPoint& point = ir.points[p];
    const Vec3& v = point.v_W;
    const double depth = point.depth;
    const double sum =
        ((point.p_PV.x() + point.p_PV.y()) + (point.p_PV.z() + v.x())) + ((v.y() + v.z()) + depth);
    nan_if_bad += sum - sum;
    if (!(depth > 0.0)) continue;
    if (point.pair != current) {
      if (point.pair < 0 || static_cast<std::size_t>(point.pair) >= pair_count) continue;
      current = point.pair;
      const auto i = static_cast<std::size_t>(current);
      const TickPair& pair = ir.pairs[i];
      n = pair.n_W;
      c = pair.c_W;
      R_WQ = carried_R_WQ_[i];
      p_WQ = carried_p_WQ_[i];
      pair_key = pair.key;
      with_friction = mu > 0.0 && !first_tick_[i];
    }
    const int point_index = static_cast<int>(p);
    const Vec3 r = v - x_p;
    if (k == capacity) {
      full = true;
      continue;
    }
    push(n, r, depth, ProxyRowKind::kNormal, point_index, current, RowIdOf(pair_key, p, false));
    ++contacts;
    ++pair_rows_[static_cast<std::size_t>(current)];
    if (!with_friction) continue;

    // Friction cone of eq. 3.9 and the tangential row of corrected eq. 3.10. With v_q the
    // previous proxy point, v_qs its projection onto the plane and v_ps = v + δn the pointer
    // point's: s = v_qs − v_ps = (v_q − v) − ((v_q − c)·n + δ) n.
    const Vec3 v_q = R_WQ * point.p_PV + p_WQ;
    const Vec3 s = (v_q - v) - ((v_q - c).dot(n) + depth) * n;
    const double slip = s.norm();
    if (!(slip > kMinSlip)) continue;
    if (k == capacity) {
      full = true;
      continue;
    }
    const double radius = mu * depth;  // ρ_i = μ δ_i
    const bool slides = slip > radius;
    push(s * (1.0 / slip), r, slides ? radius : slip,
         slides ? ProxyRowKind::kSliding : ProxyRowKind::kSticking, point_index, current,
         RowIdOf(pair_key, p, true));
    ++(slides ? sliding : sticking);
  }
  row_count_ = k;
  diag->contacts = contacts;
  diag->sticking_rows = sticking;
  diag->sliding_rows = sliding;
  diag->warm_rows = warm;
  if (full) diag->status |= kProxyStatusRowsFull;
  return !std::isnan(nan_if_bad);
}

// SPEC §3.6 / I5, made consistent with what the user feels: pair i's rows contribute
// Δr_i = Σ f_k a_k and Δθ_i = Σ f_k R_w⁻¹(r_k × a_k) to the proxy offset (Σ_i Δr_i = Δr,
// Σ_i Δθ_i = Δθ), so it pushes the pointer with the spring–damper share
// F_i = k_t Δr_i + d_t (Δr_i − Δr_i,prev)/dt and τ_i = k_r Δθ_i + d_r (Δθ_i − Δθ_i,prev)/dt
// about the pointer origin. The object receives −(F_i, τ_i), moved to its COM. Summed over
// the pairs this is exactly minus the rendered wrench (action = reaction). SPEC's per-row
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
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) {
    const TickPair& pair = ir.pairs[i];
    Wrench w_W;  // on the object, torque about its COM
    if (!pair.is_static && pair_rows_[i] > 0) {
      const Vec3 force =
          settings_.k_t * dr_pair_[i] + settings_.d_t * (dr_pair_[i] - previous_dr_pair_[i]) / dt;
      const Vec3 torque = settings_.k_r * dtheta_pair_[i] +
                          settings_.d_r * (dtheta_pair_[i] - previous_dtheta_pair_[i]) / dt;
      w_W.f = -force;
      w_W.tau = -(torque + (X_WP.p - pair.p_WCm).cross(force));
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

void AddReactionImpulses(const ProxyOutput& out, double dt, ir::HapticReport* report) noexcept {
  AddReactionImpulses(out.reactions, dt, report);
}

void AddReactionImpulses(const FixedVector<ProxyPairReaction, ir::kMaxGeometricPairs>& reactions,
                         double dt, ir::HapticReport* report) noexcept {
  // Sum this tick's reactions per body first, so last_force is the body's whole force.
  std::array<int, ir::kMaxGeometricPairs> bodies{};
  std::array<Wrench, ir::kMaxGeometricPairs> sums{};
  std::size_t count = 0;
  for (const ProxyPairReaction& r : reactions) {
    if (r.is_static || r.body < 0) continue;
    std::size_t b = 0;
    while (b < count && bodies[b] != r.body) ++b;
    if (b == count) bodies[count++] = r.body;
    sums[b].f += r.w_W.f;
    sums[b].tau += r.w_W.tau;
  }
  for (ir::BodyImpulse& entry : report->impulses) entry.last_force = Vec3::Zero();
  for (std::size_t b = 0; b < count; ++b) {
    if (sums[b].f.isZero(0.0) && sums[b].tau.isZero(0.0)) continue;
    report->AddImpulse(bodies[b], sums[b].f * dt, sums[b].tau * dt, sums[b].f);
  }
}

}  // namespace mrh::render
