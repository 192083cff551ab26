// SPDX-License-Identifier: Apache-2.0
// Chebyshev centre of a halfspace intersection: a two-phase simplex on a 4-row dual tableau.
#include "geometry/deepest_point.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace mrh::geometry::internal {
namespace {

constexpr int kRows = 4;  // Σ λ a_x, Σ λ a_y, Σ λ a_z, Σ λ
// Tableau entries smaller than this are zero: the matrix holds unit normals and ones.
constexpr double kPivotTol = 1e-12;

// Dense simplex tableau for min c·x, T x = rhs, x >= 0 with the last kRows columns artificial.
class Tableau {
 public:
  Tableau(std::span<const Halfspace> halfspaces, const Vec3& origin)
      : m_(static_cast<int>(halfspaces.size())),
        cols_(m_ + kRows),
        t_(static_cast<std::size_t>(kRows * cols_), 0.0),
        rhs_{0.0, 0.0, 0.0, 1.0},
        cost_(static_cast<std::size_t>(cols_), 0.0),
        basis_(kRows) {
    for (int j = 0; j < m_; ++j) {
      const Halfspace& h = halfspaces[static_cast<std::size_t>(j)];
      for (int i = 0; i < 3; ++i) At(i, j) = h.a[i];
      At(3, j) = 1.0;
      cost_[static_cast<std::size_t>(j)] = h.b - h.a.dot(origin);  // slack at the origin
    }
    for (int i = 0; i < kRows; ++i) {
      At(i, m_ + i) = 1.0;
      basis_[static_cast<std::size_t>(i)] = m_ + i;
    }
    scale_ = 1.0;
    for (double c : cost_) scale_ = std::max(scale_, std::abs(c));
  }

  // Phase 1 (min Σ artificials) then phase 2 (min Σ λ slack); false if infeasible or capped.
  bool Solve() {
    std::vector<double> z(static_cast<std::size_t>(cols_), 0.0);
    for (int i = 0; i < kRows; ++i) {
      for (int j = 0; j < m_; ++j) z[Index(j)] -= At(i, j);
    }
    double z_rhs = -(rhs_[0] + rhs_[1] + rhs_[2] + rhs_[3]);
    if (!Iterate(z, z_rhs, 1.0)) return false;
    if (-z_rhs > kPivotTol) return false;  // no λ: balls of any radius fit
    DriveOutArtificials();
    duals_.assign(static_cast<std::size_t>(cols_), 0.0);
    z = cost_;
    z_rhs = 0.0;
    for (int i = 0; i < kRows; ++i) {
      const double cb = cost_[Index(basis_[static_cast<std::size_t>(i)])];
      for (int j = 0; j < cols_; ++j) z[Index(j)] -= cb * At(i, j);
      z_rhs -= cb * rhs_[static_cast<std::size_t>(i)];
    }
    if (!Iterate(z, z_rhs, scale_)) return false;
    duals_ = z;
    return true;
  }

  // Optimal primal of the original LP: π_i = −(reduced cost of artificial i) = (y, s).
  Vec3 centre_offset() const {
    return -Vec3(duals_[Index(m_)], duals_[Index(m_ + 1)], duals_[Index(m_ + 2)]);
  }

 private:
  static std::size_t Index(int j) { return static_cast<std::size_t>(j); }

  double& At(int i, int j) { return t_[Index(i * cols_ + j)]; }

  double At(int i, int j) const { return t_[Index(i * cols_ + j)]; }

  // Simplex iterations with Bland's rule (smallest entering index, smallest leaving basis
  // index on ties), so degenerate pivots cannot cycle. Artificials never re-enter.
  bool Iterate(std::vector<double>& z, double& z_rhs, double cost_scale) {
    const int cap = 50 + 20 * m_;
    for (int iteration = 0; iteration < cap; ++iteration) {
      int entering = -1;
      for (int j = 0; j < m_ && entering < 0; ++j) {
        if (z[Index(j)] < -kPivotTol * cost_scale) entering = j;
      }
      if (entering < 0) return true;
      int leaving = -1;
      double best = std::numeric_limits<double>::infinity();
      for (int i = 0; i < kRows; ++i) {
        const double a = At(i, entering);
        if (a <= kPivotTol) continue;
        const double ratio = rhs_[Index(i)] / a;
        if (ratio < best ||
            (ratio == best && leaving >= 0 && basis_[Index(i)] < basis_[Index(leaving)])) {
          best = ratio;
          leaving = i;
        }
      }
      if (leaving < 0) return false;  // unbounded dual: cannot happen with Σ λ = 1
      Pivot(leaving, entering, z, z_rhs);
    }
    return false;
  }

  void Pivot(int row, int col, std::vector<double>& z, double& z_rhs) {
    const double p = At(row, col);
    for (int j = 0; j < cols_; ++j) At(row, j) /= p;
    rhs_[Index(row)] /= p;
    for (int i = 0; i < kRows; ++i) {
      const double f = At(i, col);
      if (i == row || f == 0.0) continue;
      for (int j = 0; j < cols_; ++j) At(i, j) -= f * At(row, j);
      rhs_[Index(i)] -= f * rhs_[Index(row)];
    }
    const double f = z[Index(col)];
    for (int j = 0; j < cols_; ++j) z[Index(j)] -= f * At(row, j);
    z_rhs -= f * rhs_[Index(row)];
    basis_[Index(row)] = col;
  }

  // An artificial still basic (at zero) after phase 1 is swapped for any real column in its
  // row; a row without one is redundant and stays, harmlessly, with its artificial at zero.
  void DriveOutArtificials() {
    std::vector<double> unused(static_cast<std::size_t>(cols_), 0.0);
    double unused_rhs = 0.0;
    for (int i = 0; i < kRows; ++i) {
      if (basis_[Index(i)] < m_) continue;
      for (int j = 0; j < m_; ++j) {
        if (std::abs(At(i, j)) > kPivotTol) {
          Pivot(i, j, unused, unused_rhs);
          break;
        }
      }
    }
  }

  int m_;
  int cols_;
  std::vector<double> t_;
  std::vector<double> rhs_;
  std::vector<double> cost_;
  std::vector<int> basis_;
  std::vector<double> duals_;
  double scale_ = 1.0;
};

}  // namespace

std::optional<InscribedBall> DeepestPoint(std::span<const Halfspace> halfspaces,
                                          const Vec3& origin) {
  if (halfspaces.size() < 4) return std::nullopt;
  Tableau tableau(halfspaces, origin);
  if (!tableau.Solve()) return std::nullopt;
  InscribedBall ball;
  ball.centre = origin + tableau.centre_offset();
  if (!IsFinite(ball.centre)) return std::nullopt;
  // The radius is re-measured rather than read off the LP, so roundoff cannot overstate it.
  ball.radius = std::numeric_limits<double>::infinity();
  for (const Halfspace& h : halfspaces)
    ball.radius = std::min(ball.radius, h.b - h.a.dot(ball.centre));
  return ball;
}

}  // namespace mrh::geometry::internal
