// SPDX-License-Identifier: Apache-2.0
// Splits one wrench into non-negative forces at contact points, spread as a compliant contact
// would spread them (the 6-DOF proxy's reaction over several touched objects).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mrh/core/spatial.h"

namespace mrh::render {

/// Finds forces λ_k a_k at points p_k (λ_k >= 0, a_k unit) that carry a given wrench (F, τ),
/// with τ about a reference point x, the way a linear-pressure contact carries it:
///
///   minimize Σ_k λ_k² / δ_k   subject to   Σ λ_k a_k = F,   Σ λ_k (p_k − x) × a_k = τ,   λ >= 0
///
/// with δ_k > 0 the point's weight (its penetration depth: deeper points carry more). On a flat
/// patch the answer is a pressure linear in position, clipped to >= 0.
///
/// Method: the dual is a 6-vector y with λ_k = δ_k max(0, w_k·y), w_k = (a_k, r_k × a_k):
/// φ(y) = ½ Σ δ_k max(0, w_k·y)² + ½ yᵀ D y − W·y, convex and piecewise quadratic. D is a small
/// diagonal ridge (1e-8 of the force and of the torque block's trace), which keeps y bounded
/// where W has parts no point can carry (a sideways force on a frictionless face, a torque about
/// the normal of coplanar normal rows); the carried wrench Σ λ_k w_k then misses W by that
/// part, which the caller sees and deals with. On a piece (a fixed set A of rows with w_k·y > 0)
/// φ's Hessian is H_A + D with H_A = Σ_A δ_k w_k w_kᵀ and its gradient (H_A + D) y − W, so a Newton
/// step is one 6×6 solve y ← (H_A + D)⁻¹ W, and only the rows that change sign change H_A. Each
/// step is one pass over the rows computing w_k·y (6 multiply-adds) plus a rank-one update per sign
/// change; a backtracking line search (Armijo) keeps it convergent. The step with no sign
/// change is the exact minimum. The last Solve's y warm-starts the next (successive haptic
/// ticks barely change W), so a sustained contact takes one or two passes.
///
/// Not thread safe; Solve never allocates (rows up to the capacity).
class PressureSplit {
 public:
  /// What one Solve did.
  struct Result {
    int steps = 0;           ///< Newton steps taken
    int passes = 0;          ///< passes over the rows (steps and line-search trials)
    bool converged = false;  ///< the last step changed no row's sign
    std::size_t active = 0;  ///< rows with λ > 0
  };

  /// Room for `capacity` rows (>= 1), `pair_capacity` tangent planes and as many normal groups.
  /// Throws InvalidArgument for capacity 0.
  explicit PressureSplit(std::size_t capacity, std::size_t pair_capacity = 0);

  /// Forgets the warm start (next Solve starts from the unclipped solution).
  void Reset() noexcept { has_y_ = false; }

  /// Starts a problem with no rows; add them with AddRow.
  void Begin() noexcept;
  /// Adds a row (false, and nothing added, when the capacity is reached): unit direction a,
  /// lever r = p_k − x (m), weight δ (> 0; smaller values are raised to 1e-12). A one-sided row
  /// (a normal) only pushes, λ >= 0; a two-sided one (a tangent of a point with friction, whose
  /// force may point either way) has λ of either sign, λ = δ w·y.
  bool AddRow(const Vec3& a, const Vec3& r, double depth, bool one_sided = true) noexcept;

  /// Starts a group of one-sided rows along one shared unit direction n (a pair's normal);
  /// returns its index, or -1 when the pair capacity is reached. Its rows (AddGroupRow) are
  /// rows like AddRow's, but the solve keeps their part of H as the group's moments Σδ, Σδ c,
  /// Σδ c cᵀ of c = r × n (10 multiply-adds a sign change instead of 21).
  int AddGroup(const Vec3& n) noexcept;
  /// AddRow(n of group g, r, depth) in group g (false, and nothing added, for an invalid g or
  /// a full split).
  bool AddGroupRow(int g, const Vec3& r, double depth) noexcept;

  /// Starts a tangent plane ⊥ the unit normal n (returns its index, or -1 when the plane
  /// capacity is reached). Points added to it take a force of either sign anywhere in the plane,
  /// λ = δ P (y_f + y_τ × r) with P = I − n nᵀ: exactly two two-sided rows along two orthonormal
  /// tangents at each point, but summed into the plane's moments Σδ, Σδ r, Σδ r rᵀ (10
  /// multiply-adds a point instead of two rows' 42), which is all the solve and the plane's
  /// wrench need. For points with friction, whose cone is the solver's business, not the split's.
  int AddPlane(const Vec3& n) noexcept;
  /// Adds a point at lever r (m) with weight δ (> 0; smaller values are raised to 1e-12) to
  /// plane p (ignored for an invalid p).
  void AddTangentPoint(int p, const Vec3& r, double depth) noexcept;

  std::size_t plane_count() const noexcept { return plane_count_; }

  /// Group g's direction n (g valid).
  const Vec3& group_direction(int g) const noexcept {
    return group_n_[static_cast<std::size_t>(g)];
  }

  /// The wrench plane p's points carry in the last Solve: force (N) and moment about x (N·m).
  void PlaneWrench(int p, Vec3* force, Vec3* moment) const noexcept;

  /// Solves for F (N) and τ (N·m about x). At most `max_steps` Newton steps (>= 1).
  Result Solve(const Vec3& F, const Vec3& tau, int max_steps = 20) noexcept;

  std::size_t size() const noexcept { return count_; }

  std::size_t capacity() const noexcept { return rows_.size(); }

  /// Row k's direction a.
  Vec3 direction(std::size_t k) const noexcept {
    return Vec3(rows_[k].w[0], rows_[k].w[1], rows_[k].w[2]);
  }

  /// λ_k of the last Solve (N): >= 0 for one-sided rows.
  double lambda(std::size_t k) const noexcept;

 private:
  struct Row {
    std::array<double, 6> w;  // (a, r × a)
    double d;
    std::int32_t group;       // normal group, or -1
    std::uint32_t one_sided;  // 1 or 0 (one 64-byte line per row)
  };

  // Weighted moments of vectors v_k: Σδ, Σδ v, Σδ v vᵀ (xx, xy, xz, yy, yz, zz). A plane's of
  // its points' levers r; a normal group's, on a piece, of c = r × n over its active rows.
  struct Moments {
    double s0 = 0.0;
    std::array<double, 3> s1{};
    std::array<double, 6> s2{};

    void Add(double d, double x, double y, double z) noexcept {
      const double dx = d * x, dy = d * y, dz = d * z;
      s0 += d;
      s1[0] += dx;
      s1[1] += dy;
      s1[2] += dz;
      s2[0] += dx * x;
      s2[1] += dx * y;
      s2[2] += dx * z;
      s2[3] += dy * y;
      s2[4] += dy * z;
      s2[5] += dz * z;
    }
  };

  using Sym6 = std::array<double, 21>;  // lower triangle, row by row

  struct Plane {
    Vec3 n = Vec3::Zero();
    Moments r;  // of the levers
    Sym6 h{};   // its Hessian block, built by Solve
  };

  static void BuildPlane(Plane* plane, std::array<double, 6>* traces) noexcept;
  static void AddOuter(Sym6* h, const std::array<double, 6>& w, double d) noexcept;
  // Pass at y: signs into trial_active_; (h, moments), the current piece's H, become the
  // trial's by the rows that change sign.
  std::size_t Pass(const std::array<double, 6>& y, Sym6* h, Moments* moments) noexcept;
  void AddRowTo(std::size_t k, double sign, Sym6* h, Moments* moments) const noexcept;
  // h plus the groups' parts.
  Sym6 Assembled(const Sym6& h, const Moments* moments) const noexcept;
  double Objective(const Sym6& h, const std::array<double, 6>& y) const noexcept;
  std::array<double, 6> Minimizer(const Sym6& h) const noexcept;

  // A line search's accepted point: y, its piece's H (h and trial_moments_), the step length
  // and how many rows changed sign.
  struct Trial {
    std::array<double, 6> y{};
    Sym6 h{};
    double t = 1.0;
    std::size_t changes = 0;
  };

  // Solve's phases (see the .cc).
  Sym6 BuildBase() noexcept;
  void ClearMoments() noexcept;
  void StartCold(const Sym6& base, Sym6* h) noexcept;
  void TakeSigns(Sym6* h, Result* result) noexcept;
  void EnterPiece(const Sym6& base, Sym6* h, Result* result) noexcept;
  Trial LineSearch(const Sym6& h, const std::array<double, 6>& dy, double phi, double slope,
                   Result* result) noexcept;
  bool Step(Sym6* h, Result* result) noexcept;

  std::vector<Row> rows_;
  std::vector<unsigned char> active_, trial_active_;
  std::vector<Plane> planes_;
  std::vector<Vec3> group_n_;
  std::vector<Moments> moments_, trial_moments_;
  std::size_t group_count_ = 0;
  std::size_t count_ = 0;
  std::size_t plane_count_ = 0;
  std::array<double, 6> target_{};
  std::array<double, 6> ridge_{};
  std::array<double, 6> y_{};
  bool has_y_ = false;
};

}  // namespace mrh::render
