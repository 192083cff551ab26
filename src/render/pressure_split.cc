// SPDX-License-Identifier: Apache-2.0
// Piecewise-Newton solve of the pressure split's dual (see pressure_split.h).
#include "mrh/render/pressure_split.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <utility>

#include "mrh/core/error.h"

namespace mrh::render {
namespace {

using Vec6 = std::array<double, 6>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// The ridge D, relative to the force and torque blocks' traces.
constexpr double kRidge = 1e-8;
// Where no lever carries torque (every point at the reference point), the torque block's
// ridge is that of 1 mm levers, so y stays finite.
constexpr double kMinLever2 = 1e-6;
constexpr double kArmijo = 1e-4;
constexpr int kMaxHalvings = 30;

double Dot(const Vec6& a, const Vec6& b) noexcept {
  return ((a[0] * b[0] + a[1] * b[1]) + (a[2] * b[2] + a[3] * b[3])) + (a[4] * b[4] + a[5] * b[5]);
}

Mat3 Skew(const Vec3& v) noexcept {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

// (S + diag(d)) y with S the lower triangle stored row by row.
template <typename Sym>
Vec6 Times(const Sym& h, const Vec6& ridge, const Vec6& y) noexcept {
  Vec6 out{};
  std::size_t e = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    for (std::size_t j = 0; j < i; ++j, ++e) {
      out[i] += h[e] * y[j];
      out[j] += h[e] * y[i];
    }
    out[i] += (h[e++] + ridge[i]) * y[i];
  }
  return out;
}

}  // namespace

PressureSplit::PressureSplit(std::size_t capacity, std::size_t pair_capacity) {
  if (capacity == 0) {
    throw InvalidArgument("PressureSplit: capacity = 0 rows; expected >= 1");
  }
  rows_.resize(capacity);
  active_.resize(capacity);
  trial_active_.resize(capacity);
  planes_.resize(pair_capacity);
  group_n_.resize(pair_capacity);
  moments_.resize(pair_capacity);
  trial_moments_.resize(pair_capacity);
}

void PressureSplit::Begin() noexcept {
  count_ = 0;
  plane_count_ = 0;
  group_count_ = 0;
  ridge_.fill(0.0);  // holds the traces until Solve
}

bool PressureSplit::AddRow(const Vec3& a, const Vec3& r, double depth, bool one_sided) noexcept {
  if (count_ == rows_.size()) return false;
  const Vec3 c = r.cross(a);
  Row& row = rows_[count_++];
  row.w = {a.x(), a.y(), a.z(), c.x(), c.y(), c.z()};
  row.d = std::max(depth, 1e-12);
  row.group = -1;
  row.one_sided = one_sided ? 1u : 0u;
  ridge_[0] += row.d * a.squaredNorm();
  ridge_[3] += row.d * c.squaredNorm();
  return true;
}

int PressureSplit::AddGroup(const Vec3& n) noexcept {
  if (group_count_ == group_n_.size()) return -1;
  group_n_[group_count_] = n;
  return static_cast<int>(group_count_++);
}

bool PressureSplit::AddGroupRow(int g, const Vec3& r, double depth) noexcept {
  if (g < 0 || static_cast<std::size_t>(g) >= group_count_) return false;
  if (!AddRow(group_n_[static_cast<std::size_t>(g)], r, depth)) return false;
  rows_[count_ - 1].group = g;
  return true;
}

int PressureSplit::AddPlane(const Vec3& n) noexcept {
  if (plane_count_ == planes_.size()) return -1;
  Plane& plane = planes_[plane_count_];
  plane.n = n;
  plane.r = Moments{};
  return static_cast<int>(plane_count_++);
}

void PressureSplit::AddTangentPoint(int p, const Vec3& r, double depth) noexcept {
  if (p < 0 || static_cast<std::size_t>(p) >= plane_count_) return;
  Plane& plane = planes_[static_cast<std::size_t>(p)];
  plane.r.Add(std::max(depth, 1e-12), r.x(), r.y(), r.z());
}

// A plane's Hessian Σ δ Jᵀ P J over its points, J = [I, −[r]×] (u = J y = y_f + y_τ × r):
// [[Σδ P, −P [s1]×], [[s1]× P, tr(S2) I − S2 − [n]× S2 [n]×ᵀ]]. Adds its traces (those of two
// tangent rows a point: 2 Σδ and tr(S2) + nᵀ S2 n) to `traces`.
void PressureSplit::BuildPlane(Plane* plane, Vec6* traces) noexcept {
  const Vec3& n = plane->n;
  const Moments& levers = plane->r;
  const auto& q = levers.s2;
  Mat3 s2;
  s2 << q[0], q[1], q[2], q[1], q[3], q[4], q[2], q[4], q[5];
  const Mat3 p = Mat3::Identity() - n * n.transpose();
  const Mat3 n_x = Skew(n);
  const Mat3 ff = levers.s0 * p;
  const Mat3 tf = Skew(Vec3(levers.s1[0], levers.s1[1], levers.s1[2])) * p;
  const Mat3 tt = s2.trace() * Mat3::Identity() - s2 - n_x * s2 * n_x.transpose();
  Mat6 m;
  m << ff, tf.transpose(), tf, tt;
  std::size_t e = 0;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j <= i; ++j) plane->h[e++] = m(i, j);
  }
  (*traces)[0] += 2.0 * levers.s0;
  (*traces)[3] += s2.trace() + n.dot(s2 * n);
}

void PressureSplit::PlaneWrench(int p, Vec3* force, Vec3* moment) const noexcept {
  if (p < 0 || static_cast<std::size_t>(p) >= plane_count_) {
    force->setZero();
    moment->setZero();
    return;
  }
  const Vec6 w = Times(planes_[static_cast<std::size_t>(p)].h, Vec6{}, y_);
  *force = Vec3(w[0], w[1], w[2]);
  *moment = Vec3(w[3], w[4], w[5]);
}

// The hot loop of a solve (21 multiply-adds a row): unrolled.
void PressureSplit::AddOuter(Sym6* h, const Vec6& w, double d) noexcept {
  std::size_t e = 0;
#pragma GCC unroll 6
  for (std::size_t i = 0; i < 6; ++i) {
    const double dw = d * w[i];
#pragma GCC unroll 6
    for (std::size_t j = 0; j <= i; ++j) (*h)[e++] += dw * w[j];
  }
}

// Row k into (sign +1) or out of (−1) a piece's H: its group's moments, or h itself.
void PressureSplit::AddRowTo(std::size_t k, double sign, Sym6* h, Moments* moments) const noexcept {
  const Row& row = rows_[k];
  const double d = sign * row.d;
  if (row.group < 0) {
    AddOuter(h, row.w, d);
    return;
  }
  moments[static_cast<std::size_t>(row.group)].Add(d, row.w[3], row.w[4], row.w[5]);
}

// Σ over a group's rows of δ w wᵀ, w = (n, c): [[s0 n nᵀ, n s1ᵀ], [s1 nᵀ, s2]].
PressureSplit::Sym6 PressureSplit::Assembled(const Sym6& h, const Moments* moments) const noexcept {
  Sym6 out = h;
  for (std::size_t g = 0; g < group_count_; ++g) {
    const Moments& m = moments[g];
    const Vec3& n = group_n_[g];
    const double nn[3] = {n.x(), n.y(), n.z()};
    std::size_t e = 0;
    for (std::size_t i = 0; i < 3; ++i) {  // force block
      for (std::size_t j = 0; j <= i; ++j) out[e++] += m.s0 * nn[i] * nn[j];
    }
    static constexpr std::size_t kS2[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
    for (std::size_t i = 0; i < 3; ++i) {  // torque rows: s1_i nᵀ, then Σδ c_i c_j
      for (std::size_t j = 0; j < 3; ++j) out[e++] += m.s1[i] * nn[j];
      for (std::size_t j = 0; j <= i; ++j) out[e++] += m.s2[kS2[i][j]];
    }
  }
  return out;
}

// Returns how many rows changed sign (see the header).
std::size_t PressureSplit::Pass(const Vec6& y, Sym6* h, Moments* moments) noexcept {
  std::size_t changes = 0;
  for (std::size_t k = 0; k < count_; ++k) {
    const Row& row = rows_[k];
    const unsigned char on = (row.one_sided == 0u || Dot(row.w, y) > 0.0) ? 1 : 0;
    trial_active_[k] = on;
    if (on != active_[k]) {
      AddRowTo(k, on ? 1.0 : -1.0, h, moments);
      ++changes;
    }
  }
  return changes;
}

// φ(y) on the piece with Hessian h: ½ yᵀ (h + D) y − W·y.
double PressureSplit::Objective(const Sym6& h, const Vec6& y) const noexcept {
  return 0.5 * Dot(y, Times(h, ridge_, y)) - Dot(target_, y);
}

// The piece's minimizer (h + D)⁻¹ W.
Vec6 PressureSplit::Minimizer(const Sym6& h) const noexcept {
  Mat6 m;
  std::size_t e = 0;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j <= i; ++j, ++e) m(i, j) = m(j, i) = h[e];
    m(i, i) += ridge_[static_cast<std::size_t>(i)];
  }
  const Eigen::Matrix<double, 6, 1> w(target_.data());
  const Eigen::Matrix<double, 6, 1> y = m.ldlt().solve(w);
  return {y[0], y[1], y[2], y[3], y[4], y[5]};
}

// The planes' part of H, the same on every piece; sets the ridge from the rows' and planes'
// traces.
PressureSplit::Sym6 PressureSplit::BuildBase() noexcept {
  Sym6 base{};
  for (std::size_t p = 0; p < plane_count_; ++p) {
    BuildPlane(&planes_[p], &ridge_);
    for (std::size_t e = 0; e < base.size(); ++e) base[e] += planes_[p].h[e];
  }
  const double force_trace = std::max(ridge_[0], 1e-300);
  const double torque_trace = std::max(ridge_[3], kMinLever2 * force_trace);
  for (std::size_t i = 0; i < 3; ++i) {
    ridge_[i] = kRidge * force_trace;
    ridge_[i + 3] = kRidge * torque_trace;
  }
  return base;
}

void PressureSplit::ClearMoments() noexcept {
  std::fill(moments_.begin(), moments_.begin() + static_cast<std::ptrdiff_t>(group_count_),
            Moments{});
}

// Every row active, y their minimizer.
void PressureSplit::StartCold(const Sym6& base, Sym6* h) noexcept {
  *h = base;
  ClearMoments();
  for (std::size_t k = 0; k < count_; ++k) {
    AddRowTo(k, 1.0, h, moments_.data());
    active_[k] = 1;
  }
  y_ = Minimizer(Assembled(*h, moments_.data()));
}

// y's signs become the current piece's, H (h, moments_) with them.
void PressureSplit::TakeSigns(Sym6* h, Result* result) noexcept {
  (void)Pass(y_, h, moments_.data());
  std::swap(active_, trial_active_);
  ++result->passes;
}

// The first piece: the old y's signs, or a cold start's when there is no old y or it presses
// no row.
void PressureSplit::EnterPiece(const Sym6& base, Sym6* h, Result* result) noexcept {
  if (has_y_) {
    std::fill(active_.begin(), active_.begin() + static_cast<std::ptrdiff_t>(count_), 0);
  } else {
    StartCold(base, h);
  }
  TakeSigns(h, result);
  if (has_y_ && std::find(active_.begin(), active_.begin() + static_cast<std::ptrdiff_t>(count_),
                          1) == active_.begin() + static_cast<std::ptrdiff_t>(count_)) {
    StartCold(base, h);
    TakeSigns(h, result);
  }
}

// Halves t from 1 until Armijo's condition holds at y + t dy (or after kMaxHalvings); the
// trial's signs are in trial_active_, its H in (trial.h, trial_moments_).
PressureSplit::Trial PressureSplit::LineSearch(const Sym6& h, const Vec6& dy, double phi,
                                               double slope, Result* result) noexcept {
  Trial trial;
  for (int halving = 0;; ++halving) {
    for (std::size_t i = 0; i < 6; ++i) trial.y[i] = y_[i] + trial.t * dy[i];
    trial.h = h;
    std::copy_n(moments_.begin(), group_count_, trial_moments_.begin());
    trial.changes = Pass(trial.y, &trial.h, trial_moments_.data());
    ++result->passes;
    if (Objective(Assembled(trial.h, trial_moments_.data()), trial.y) <=
            phi + kArmijo * trial.t * slope ||
        halving == kMaxHalvings)
      break;
    trial.t *= 0.5;
  }
  return trial;
}

// One damped Newton step toward the current piece's minimizer. Returns false when the solve
// is over (result->converged set): no descent left, or a full step that changed no sign.
bool PressureSplit::Step(Sym6* h, Result* result) noexcept {
  const Sym6 full = Assembled(*h, moments_.data());
  const Vec6 y_next = Minimizer(full);
  Vec6 dy, gradient = Times(full, ridge_, y_);
  for (std::size_t i = 0; i < 6; ++i) {
    dy[i] = y_next[i] - y_[i];
    gradient[i] -= target_[i];
  }
  const double slope = Dot(gradient, dy);  // −gᵀ(h + D)⁻¹g <= 0
  if (!(slope < 0.0)) {  // y already minimizes its piece, which no sign change left
    result->converged = std::isfinite(slope);
    return false;
  }
  const Trial trial = LineSearch(*h, dy, Objective(full, y_), slope, result);
  y_ = trial.y;
  *h = trial.h;
  std::swap(moments_, trial_moments_);
  std::swap(active_, trial_active_);
  ++result->steps;
  if (trial.changes == 0 && trial.t == 1.0) {  // the piece's minimizer, and still its piece
    result->converged = true;
    return false;
  }
  return true;
}

PressureSplit::Result PressureSplit::Solve(const Vec3& F, const Vec3& tau, int max_steps) noexcept {
  Result result;
  target_ = {F.x(), F.y(), F.z(), tau.x(), tau.y(), tau.z()};
  const Sym6 base = BuildBase();
  // The current piece's H is Assembled(h, moments_).
  Sym6 h = base;
  ClearMoments();
  EnterPiece(base, &h, &result);
  while (result.steps < max_steps && Step(&h, &result)) {
  }
  has_y_ = true;
  for (const double v : y_) has_y_ = has_y_ && std::isfinite(v);
  if (!has_y_) {
    y_.fill(0.0);
    result.converged = false;
  }
  for (std::size_t k = 0; k < count_; ++k) result.active += lambda(k) != 0.0 ? 1 : 0;
  return result;
}

double PressureSplit::lambda(std::size_t k) const noexcept {
  if (k >= count_) return 0.0;
  const Row& row = rows_[k];
  const double s = Dot(row.w, y_);
  return row.d * (row.one_sided != 0u ? std::max(0.0, s) : s);
}

}  // namespace mrh::render
