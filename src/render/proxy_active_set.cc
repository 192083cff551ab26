// SPDX-License-Identifier: Apache-2.0
// Goldfarb–Idnani dual active-set method on the 6-D proxy program (see proxy_active_set.h).
#include "mrh/render/proxy_active_set.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "mrh/core/assert.h"
#include "mrh/core/error.h"

namespace mrh::render {
namespace {

// A new row's normal counts as dependent on the active ones when the part of it orthogonal to
// them is below this fraction of its length (squared): 1e-10 keeps R's condition number below
// ~1e5 times that of the rows themselves.
constexpr double kRankTolerance = 1e-10;
// Dual direction entries below this are zero (rounding of the back-substitution).
constexpr double kDualTolerance = 1e-14;

using Vec6 = std::array<double, 6>;

double Dot(const Vec6& a, const Vec6& b) noexcept {
  return ((a[0] * b[0] + a[1] * b[1]) + (a[2] * b[2] + a[3] * b[3])) + (a[4] * b[4] + a[5] * b[5]);
}

// v -= s·q
void SubtractScaled(Vec6* v, double s, const Vec6& q) noexcept {
  for (int i = 0; i < 6; ++i)
    (*v)[static_cast<std::size_t>(i)] -= s * q[static_cast<std::size_t>(i)];
}

}  // namespace

ProxyActiveSetSolver::ProxyActiveSetSolver(std::size_t capacity) {
  if (capacity == 0) {
    throw InvalidArgument(
        "ProxyActiveSetSolver: capacity = 0 rows; expected >= 1; pass the most constraint rows "
        "one tick can have (2 per contact point with friction)");
  }
  capacity_ = capacity;
}

// Adds the most violated row until none is (returns true) or the steps run out (false); *steps
// counts them, *violation is the last scan's.
bool ProxyActiveSetSolver::AddRowsUntilFeasible(const ProxySolverSettings& settings, int* steps,
                                                double* violation) noexcept {
  for (;;) {
    const int p = MostViolated(settings.tolerance, violation);
    if (p < 0) return true;
    if (*steps >= settings.max_iterations || !AddRow(p, steps, settings.max_iterations)) {
      return false;
    }
  }
}

ProxySolveResult ProxyActiveSetSolver::Solve(std::span<const ProxyRow> rows,
                                             const Mat3& rotation_weight_inverse,
                                             const ProxySolverSettings& settings,
                                             std::span<double> f, Vec3* dr, Vec3* dtheta) noexcept {
  MRH_ASSERT(rows.size() == f.size() && rows.size() <= capacity_);
  MRH_ASSERT(settings.max_iterations >= 1);
  rows_ = rows.first(std::min(rows.size(), capacity_));
  // R_w⁻¹ = K Kᵀ; Δθ = K y_θ.
  const Eigen::LLT<Mat3> llt(rotation_weight_inverse);
  const Mat3 k_lower = llt.matrixL();
  k_ = {k_lower(0, 0), k_lower(1, 0), k_lower(2, 0), k_lower(1, 1), k_lower(2, 1), k_lower(2, 2)};
  SetActiveFromStart(f.first(rows_.size()));

  ProxySolveResult result;
  int steps = 0;
  double violation = 0.0;
  result.converged = AddRowsUntilFeasible(settings, &steps, &violation);
  // The multipliers were updated step by step; with large ones (R_w ≫ |r|² makes rotation
  // cheap in f) that drifts from y by rounding. At the solution the active rows hold with
  // equality, so solving for them afresh gives consistent λ and y. Without steps, λ and y
  // already come from that solve (SetActiveFromStart). The reported violation is the last
  // scan's: the fresh solve moves y by rounding only, and another scan of every row would cost
  // a seventh of a typical tick's solve.
  if (result.converged && count_ > 0 && steps > 0) SolveEqualityActive();
  result.iterations = steps;
  result.max_change = std::max(0.0, -violation);

  for (std::size_t k = 0; k < rows_.size(); ++k) f[k] = 0.0;
  for (int i = 0; i < count_; ++i) {
    f[static_cast<std::size_t>(active_[static_cast<std::size_t>(i)])] =
        std::max(0.0, lambda_[static_cast<std::size_t>(i)]);
  }
  *dr = Vec3(y_[0], y_[1], y_[2]);
  *dtheta = k_lower * Vec3(y_[3], y_[4], y_[5]);
  rows_ = {};
  return result;
}

// Scalar code on purpose: a cross product handed to Eigen as a temporary went through the
// stack and stalled on store forwarding.
ProxyActiveSetSolver::Vec6 ProxyActiveSetSolver::Normal(int row) const noexcept {
  // (a, Kᵀ c), c = r × a, with K lower triangular.
  const ProxyRow& r = rows_[static_cast<std::size_t>(row)];
  const double a0 = r.a.x(), a1 = r.a.y(), a2 = r.a.z();
  const double r0 = r.r.x(), r1 = r.r.y(), r2 = r.r.z();
  const double c0 = r1 * a2 - r2 * a1;
  const double c1 = r2 * a0 - r0 * a2;
  const double c2 = r0 * a1 - r1 * a0;
  return {a0, a1, a2, k_[0] * c0 + k_[1] * c1 + k_[2] * c2, k_[3] * c1 + k_[4] * c2, k_[5] * c2};
}

bool ProxyActiveSetSolver::IsActive(std::size_t row) const noexcept {
  for (int i = 0; i < count_; ++i) {
    if (static_cast<std::size_t>(active_[static_cast<std::size_t>(i)]) == row) return true;
  }
  return false;
}

// Warm start: the rows with f > 0 (independent ones, at most 6) as equalities, then drop those
// whose multiplier is negative until the start is dual feasible (λ >= 0), which is what the dual
// method needs; y is then the minimum of the program restricted to the active rows.
void ProxyActiveSetSolver::SetActiveFromStart(std::span<double> f) noexcept {
  count_ = 0;
  y_ = {};
  for (std::size_t k = 0; k < f.size() && count_ < kDim; ++k) {
    if (!(f[k] > 0.0) || !std::isfinite(f[k])) continue;  // most rows: one compare
    active_[static_cast<std::size_t>(count_)] = static_cast<int>(k);
    ++count_;
    if (!Factorize()) --count_;  // dependent on the rows already taken
  }
  if (count_ == 0) return;
  Factorize();
  for (;;) {
    SolveEqualityActive();
    int worst = -1;
    double most_negative = 0.0;
    for (int i = 0; i < count_; ++i) {
      if (lambda_[static_cast<std::size_t>(i)] < most_negative) {
        most_negative = lambda_[static_cast<std::size_t>(i)];
        worst = i;
      }
    }
    if (worst < 0) return;
    DropActive(worst);
    if (count_ == 0) {
      y_ = {};
      return;
    }
  }
}

// Gram–Schmidt (twice, for orthogonality to rounding) of the active normals into Q and R.
// Returns false if the last column is dependent on the others.
bool ProxyActiveSetSolver::Factorize() noexcept {
  for (int c = 0; c < count_; ++c) {
    const auto cu = static_cast<std::size_t>(c);
    Vec6 v = Normal(active_[cu]);
    const double length2 = Dot(v, v);
    for (int i = 0; i < kDim; ++i) r_[static_cast<std::size_t>(i)][cu] = 0.0;
    for (int pass = 0; pass < 2; ++pass) {
      for (int i = 0; i < c; ++i) {
        const auto iu = static_cast<std::size_t>(i);
        const double d = Dot(q_[iu], v);
        r_[iu][cu] += d;
        SubtractScaled(&v, d, q_[iu]);
      }
    }
    const double rest2 = Dot(v, v);
    if (!(rest2 > kRankTolerance * length2)) return false;
    const double rest = std::sqrt(rest2);
    r_[cu][cu] = rest;
    for (std::size_t i = 0; i < 6; ++i) q_[cu][i] = v[i] / rest;
  }
  return true;
}

// λ and y of min ½|y|² s.t. n_kᵀ y = rhs_k for the active rows: with N = Q R,
// Rᵀ w = rhs, R λ = w, y = Q w.
void ProxyActiveSetSolver::SolveEqualityActive() noexcept {
  std::array<double, kDim> w{};
  for (int i = 0; i < count_; ++i) {
    const auto iu = static_cast<std::size_t>(i);
    double s = rows_[static_cast<std::size_t>(active_[iu])].rhs;
    for (int k = 0; k < i; ++k)
      s -= r_[static_cast<std::size_t>(k)][iu] * w[static_cast<std::size_t>(k)];
    w[iu] = s / r_[iu][iu];
  }
  for (int i = count_ - 1; i >= 0; --i) {
    const auto iu = static_cast<std::size_t>(i);
    double s = w[iu];
    for (int k = i + 1; k < count_; ++k) {
      s -= r_[iu][static_cast<std::size_t>(k)] * lambda_[static_cast<std::size_t>(k)];
    }
    lambda_[iu] = s / r_[iu][iu];
  }
  y_ = {};
  for (int i = 0; i < count_; ++i) {
    const auto iu = static_cast<std::size_t>(i);
    for (std::size_t d = 0; d < 6; ++d) y_[d] += w[iu] * q_[iu][d];
  }
}

namespace {

// Two doubles, one per row: the slack scan below handles rows two at a time. Each lane does
// exactly the scalar operations in the scalar order (SSE2 lanes round as scalar SSE2 does, and
// -ffp-contract=off keeps multiply and add apart), so the slacks are bit-identical.
using TwoRows = double __attribute__((vector_size(16)));

// Rows k and k + 1 side by side: each lane one row's direction, lever arm and rhs.
struct TwoRowData {
  TwoRows a[3];
  TwoRows r[3];
  TwoRows rhs;
};

TwoRowData LoadTwo(const ProxyRow* rows, std::size_t k) noexcept {
  const ProxyRow& p = rows[k];
  const ProxyRow& q = rows[k + 1];
  return {{TwoRows{p.a.x(), q.a.x()}, TwoRows{p.a.y(), q.a.y()}, TwoRows{p.a.z(), q.a.z()}},
          {TwoRows{p.r.x(), q.r.x()}, TwoRows{p.r.y(), q.r.y()}, TwoRows{p.r.z(), q.r.z()}},
          TwoRows{p.rhs, q.rhs}};
}

// The slack n_k·y − rhs_k of a row, evaluated as a_k·(Δr + Δθ × r_k) − rhs_k (see MostViolated).
// T is double (one row) or TwoRows; dr and w are Δr and Δθ.
template <typename T>
T Slack(const T (&dr)[3], const T (&w)[3], const T (&a)[3], const T (&r)[3], T rhs) noexcept {
  // Displacement of the contact point, Δr + Δθ × r.
  const T u0 = dr[0] + (w[1] * r[2] - w[2] * r[1]);
  const T u1 = dr[1] + (w[2] * r[0] - w[0] * r[2]);
  const T u2 = dr[2] + (w[0] * r[1] - w[1] * r[0]);
  return (a[0] * u0 + a[1] * u1) + a[2] * u2 - rhs;
}

}  // namespace

// The inactive row with the most negative n_k·y − rhs_k below −tolerance, or −1. The slack is
// evaluated as a_k·(Δr + Δθ × r_k) − rhs_k on the rows as given (n_k·y in the proxy's own
// coordinates), so no per-row data is stored: in sustained contact the warm start is the
// solution and this one pass over the rows is all the solver reads of them. Rows go two at a
// time; a pair of rows whose slacks are both no lower than the running minimum (nearly every
// pair) is passed over, the others are taken one after the other as in a scalar scan.
int ProxyActiveSetSolver::MostViolated(double tolerance, double* violation) const noexcept {
  // Δθ = K y_θ.
  const double w[3] = {k_[0] * y_[3], k_[1] * y_[3] + k_[3] * y_[4],
                       k_[2] * y_[3] + k_[4] * y_[4] + k_[5] * y_[5]};
  const double dr[3] = {y_[0], y_[1], y_[2]};
  const TwoRows w2[3] = {TwoRows{w[0], w[0]}, TwoRows{w[1], w[1]}, TwoRows{w[2], w[2]}};
  const TwoRows dr2[3] = {TwoRows{dr[0], dr[0]}, TwoRows{dr[1], dr[1]}, TwoRows{dr[2], dr[2]}};
  std::size_t best = 0;
  double lowest = std::numeric_limits<double>::infinity();
  const std::size_t m = rows_.size();
  const ProxyRow* const rows = rows_.data();
  // A new running minimum is rare, so the active-set test (<= 6 compares) costs little.
  const auto consider = [&](std::size_t k, double s) noexcept {
    if (s < lowest && !IsActive(k)) {
      lowest = s;
      best = k;
    }
  };
  std::size_t k = 0;
  for (; k + 1 < m; k += 2) {
    const TwoRowData two = LoadTwo(rows, k);
    const TwoRows s = Slack(dr2, w2, two.a, two.r, two.rhs);
    if (!(s[0] < lowest) && !(s[1] < lowest)) continue;
    consider(k, s[0]);
    consider(k + 1, s[1]);
  }
  for (; k < m; ++k) {
    const ProxyRow& row = rows[k];
    const double a[3] = {row.a.x(), row.a.y(), row.a.z()};
    const double r[3] = {row.r.x(), row.r.y(), row.r.z()};
    consider(k, Slack(dr, w, a, r, row.rhs));
  }
  *violation = std::min(0.0, lowest);
  return lowest < -tolerance ? static_cast<int>(best) : -1;
}

// z: the part of n_p orthogonal to the active normals (two Gram–Schmidt passes), d = Qᵀ n_p.
void ProxyActiveSetSolver::Project(const Vec6& n_p, std::array<double, kDim>* d,
                                   Vec6* z) const noexcept {
  *z = n_p;
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i < count_; ++i) {
      const auto iu = static_cast<std::size_t>(i);
      const double c = Dot(q_[iu], *z);
      (*d)[iu] += c;
      SubtractScaled(z, c, q_[iu]);
    }
  }
}

// r = R⁻¹ d: the change of the active multipliers per unit of λ_p.
std::array<double, ProxyActiveSetSolver::kDim> ProxyActiveSetSolver::BackSolve(
    const std::array<double, kDim>& d) const noexcept {
  std::array<double, kDim> r{};
  for (int i = count_ - 1; i >= 0; --i) {
    const auto iu = static_cast<std::size_t>(i);
    double s = d[iu];
    for (int k = i + 1; k < count_; ++k)
      s -= r_[iu][static_cast<std::size_t>(k)] * r[static_cast<std::size_t>(k)];
    r[iu] = s / r_[iu][iu];
  }
  return r;
}

// Partial step: the first active multiplier to reach zero (its slot in *drop, −1 if none).
double ProxyActiveSetSolver::PartialStep(const std::array<double, kDim>& r,
                                         int* drop) const noexcept {
  double t_partial = std::numeric_limits<double>::infinity();
  *drop = -1;
  for (int i = 0; i < count_; ++i) {
    const auto iu = static_cast<std::size_t>(i);
    if (r[iu] > kDualTolerance) {
      const double ratio = std::max(0.0, lambda_[iu]) / r[iu];
      if (ratio < t_partial) {
        t_partial = ratio;
        *drop = i;
      }
    }
  }
  return t_partial;
}

// Row p joins the active set with multiplier lambda_p; Q and R grow by z's direction.
void ProxyActiveSetSolver::Activate(int p, double lambda_p, const std::array<double, kDim>& d,
                                    const Vec6& z, double zz) noexcept {
  const auto slot = static_cast<std::size_t>(count_);
  active_[slot] = p;
  lambda_[slot] = lambda_p;
  ++count_;
  for (int i = 0; i < count_ - 1; ++i)
    r_[static_cast<std::size_t>(i)][slot] = d[static_cast<std::size_t>(i)];
  const double rest = std::sqrt(zz);
  r_[slot][slot] = rest;
  for (std::size_t i = 0; i < 6; ++i) q_[slot][i] = z[i] / rest;
}

// One Goldfarb–Idnani major iteration for row p: steps until p is active (true), or the step
// budget runs out / the rows are infeasible (false). Each step is a full step (p becomes
// active) or a partial one (an active row's multiplier reaches 0 and the row is dropped).
bool ProxyActiveSetSolver::AddRow(int p, int* steps, int max_steps) noexcept {
  const Vec6 n_p = Normal(p);
  const double length2 = Dot(n_p, n_p);
  double lambda_p = 0.0;
  while (*steps < max_steps) {
    ++*steps;
    std::array<double, kDim> d{};
    Vec6 z;
    Project(n_p, &d, &z);
    const std::array<double, kDim> r = BackSolve(d);
    int drop = -1;
    const double t_partial = PartialStep(r, &drop);
    // Full step: to where row p holds with equality.
    const double zz = Dot(z, z);
    const bool independent = zz > kRankTolerance * length2;
    const double slack = Dot(n_p, y_) - rows_[static_cast<std::size_t>(p)].rhs;
    const double t_full =
        independent ? std::max(0.0, -slack) / zz : std::numeric_limits<double>::infinity();
    if (!independent && drop < 0) return false;  // infeasible: p contradicts the active rows
    const bool full = t_full <= t_partial;
    const double t = full ? t_full : t_partial;
    if (independent) {
      for (std::size_t i = 0; i < 6; ++i) y_[i] += t * z[i];
    }
    for (int i = 0; i < count_; ++i) {
      lambda_[static_cast<std::size_t>(i)] -= t * r[static_cast<std::size_t>(i)];
    }
    lambda_p += t;
    if (full) {
      Activate(p, lambda_p, d, z, zz);
      return true;
    }
    DropActive(drop);
  }
  return false;
}

void ProxyActiveSetSolver::DropActive(int slot) noexcept {
  for (int i = slot; i + 1 < count_; ++i) {
    active_[static_cast<std::size_t>(i)] = active_[static_cast<std::size_t>(i + 1)];
    lambda_[static_cast<std::size_t>(i)] = lambda_[static_cast<std::size_t>(i + 1)];
  }
  --count_;
  // The remaining normals were independent, so they stay so.
  const bool ok = Factorize();
  MRH_ASSERT(ok);
  (void)ok;
}

}  // namespace mrh::render
