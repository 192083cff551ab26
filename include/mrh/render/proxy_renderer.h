// SPDX-License-Identifier: Apache-2.0
// 6-DOF proxy rendering with friction cones on the interpolated geometric IR (thesis §3.2.2–3.2.4,
// eq. 3.1–3.10; docs/theory.md).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "mrh/core/fixed_vector.h"
#include "mrh/core/spatial.h"
#include "mrh/core/status_bits.h"
#include "mrh/ir/snapshot.h"
#include "mrh/render/pressure_split.h"
#include "mrh/render/proxy_active_set.h"
#include "mrh/render/proxy_solver.h"
#include "mrh/render/tick_ir.h"

namespace mrh::render {

/// Most constraint rows one tick can have: a normal and a friction row per contact point.
inline constexpr std::size_t kMaxProxyRows = 2 * ir::kMaxPairPoints;
/// Compile-time ceiling on ProxyRendererSettings::max_iterations, so a tick's work stays bounded
/// whatever the settings say.
inline constexpr int kMaxProxyIterations = 100000;

/// Status bits of one ProxyRenderer::Tick.
enum ProxyStatusBits : std::uint32_t {
  kProxyStatusOk = 0,
  kProxyStatusRowsFull = 1u << 0,  ///< more rows than max_rows: the excess was dropped
  /// The solver stopped at max_iterations above tolerance (or, active-set, the rows were
  /// contradictory).
  kProxyStatusNotConverged = 1u << 1,
  /// Non-finite pointer pose, dt <= 0 or non-finite IR data or result: the wrench is zero, the
  /// proxy is the pointer and the renderer was Reset.
  kProxyStatusBadInput = 1u << 2,
  /// kContact: a pair's force exceeded max_pair_force and every contact force of the tick was
  /// scaled down by one factor (a proxy wedged between objects whose rows nearly contradict).
  kProxyStatusPairForceLimited = 1u << 4,
};

/// The names of ProxyStatusBits (RunStats::method_status prefixes them, "proxy.rows_full").
inline constexpr std::array<StatusBitName, 4> kProxyStatusNames{{
    {kProxyStatusRowsFull, "rows_full"},
    {kProxyStatusNotConverged, "not_converged"},
    {kProxyStatusBadInput, "bad_input"},
    {kProxyStatusPairForceLimited, "pair_force_limited"},
}};
static_assert(ValidStatusBitNames(kProxyStatusNames));

/// Which algorithm solves the proxy LCP of eq. 3.4 each tick.
enum class ProxySolverKind : std::uint8_t {
  /// ProxyActiveSetSolver: exact, a few steps of O(m) each (default).
  kActiveSet,
  /// ProxySolver: the thesis' projected Gauss–Seidel (eq. 3.6), O(m) per sweep.
  kPgs,
};

/// How the rendered wrench and the objects' reactions relate to the proxy's contacts.
enum class ProxyTorqueModel : std::uint8_t {
  /// Every force is a contact force. R_w = (k_r / k_t)·I, so that the proxy's KKT conditions
  /// make its spring wrench (k_t Δr, k_r Δθ) exactly the wrench of the forces k_t f_k a_k at the
  /// rows' points. Those forces, limited to each pair's friction cone (|F_t| <= μ N) and scaled
  /// per pair by a damper on the pair's normal load, (1 + (d_t / k_t) Ṅ / N) >= 0, are what the
  /// user feels (their sum) and what each object receives (minus its own pairs' forces, at their
  /// points). rotation_weight and d_r are not used (d_r must be 0).
  kContact,
  /// Eq. 3.7–3.8 with the given R_w and d_r; each object receives its share of the rendered
  /// wrench, couple included (not a contact wrench: a point contact can be given a moment).
  /// Default.
  kThesis,
};

/// Parameters of the proxy renderer (thesis §3.2.2–3.2.3, §3.4.1). Designated initializers welcome.
struct ProxyRendererSettings {
  double k_t = 1000.0;  ///< translational spring of eq. 3.7 (N/m, >= 0)
  double d_t = 0.0;     ///< translational damper of eq. 3.7 (N·s/m, >= 0)
  double k_r = 10.0;    ///< rotational spring of eq. 3.8 (N·m/rad, >= 0)
  double d_r = 0.0;     ///< rotational damper of eq. 3.8 (N·m·s/rad, >= 0)
  /// Rotation weight R_w (m², world frame, symmetric positive definite; thesis §3.4.1), kThesis
  /// only. For the thesis recipe use RotationWeightFromInertia; a diagonal one is
  /// Vec3(...).asDiagonal().
  Mat3 rotation_weight = Mat3::Identity();
  /// Coulomb coefficient μ of the friction cones (eq. 3.9–3.10; static = kinetic, >= 0).
  /// 0 builds no friction rows. A pair whose TickPair::material has a material uses that
  /// material's friction instead, and with kContact also its stiffness and damping in place of
  /// k_t and d_t for its contact forces (kThesis keeps k_t and d_t: its wrench is one spring on
  /// the whole proxy offset).
  double mu = 0.0;
  /// kContact only: the most force one pair may carry (N, > 0). Rows that nearly contradict
  /// each other (a proxy wedged between two objects that overlap around the pointer) have
  /// solutions far from the pointer and contact forces that grow without bound; when a pair's
  /// force exceeds this, all of the tick's contact forces are scaled by one factor so that the
  /// largest is this, which keeps each in its cone and action = reaction exact.
  double max_pair_force = std::numeric_limits<double>::infinity();
  /// kContact needs k_t > 0 and k_r > 0 and d_r = 0.
  ProxyTorqueModel torque_model = ProxyTorqueModel::kThesis;
  ProxySolverKind solver = ProxySolverKind::kActiveSet;
  /// PGS sweeps or active-set steps per tick at most, in [1, kMaxProxyIterations].
  int max_iterations = 50;
  /// Active-set: stops when no row is violated by more than this (m).
  /// PGS: stops when no f_k changed more than this in a sweep (m). The change of row k is its
  /// constraint violation / c_kk, so this is a penetration tolerance. On face and edge
  /// contacts with R_w ≫ |r|² PGS converges slowly (~1700 cold sweeps to 1e-10 m for a T3.1
  /// cube face; never within 50 for a 1000-point face). In sustained contact the warm-started
  /// solve reaches 1e-7 m (~1 mN at k_t = 9000) in about 2 sweeps (T3.4 bench),
  /// while 1e-10 m mostly exhausts max_iterations.
  double tolerance = 1e-10;
  /// PGS only. If > 0, a time budget independent of the contact count: a tick with m rows runs at
  /// most max(1, max_row_updates / m) sweeps (and never more than max_iterations). PGS converges
  /// slowly on face/edge contacts when R_w ≫ |r|² (hundreds to thousands of sweeps), so a
  /// large max_iterations plus this budget lets small contact sets converge within the tick
  /// while large ones stay bounded. 0: max_iterations alone.
  std::size_t max_row_updates = 0;
  /// Row capacity, fixed at construction, in [1, kMaxProxyRows]. Rows beyond it are dropped
  /// (kProxyStatusRowsFull): normal rows take precedence over their own friction row.
  std::size_t max_rows = kMaxProxyRows;

  /// @throws mrh::InvalidArgument naming the field, its value, the expected range and the fix.
  void Validate() const;
};

/// R_w = scale · unit_mass_inertia: the thesis recipe (§3.4.1). unit_mass_inertia is the
/// pointer's inertia tensor about its origin for mass 1 (m², world-aligned frame at the pose
/// where R_w is used; for a box a_x × a_y × a_z it is diag(a_y²+a_z², a_x²+a_z², a_x²+a_y²)/12).
/// @throws mrh::InvalidArgument if scale is not finite and > 0 or the tensor is not finite,
/// symmetric and positive definite. Not RT-safe.
Mat3 RotationWeightFromInertia(const Mat3& unit_mass_inertia, double scale);

/// What a constraint row stands for.
enum class ProxyRowKind : std::uint8_t {
  kNormal,    ///< non-penetration row of eq. 3.1 (a = n, rhs = δ)
  kSticking,  ///< friction row of eq. 3.10 inside the cone: static friction (rhs = |s| <= μδ)
  kSliding,   ///< friction row on the cone boundary: kinetic friction (rhs = μδ < |s|)
};

/// Where a row came from.
struct ProxyRowInfo {
  ProxyRowKind kind = ProxyRowKind::kNormal;
  int point = -1;  ///< index into TickIr::points
  int pair = -1;   ///< index into TickIr::pairs
};

/// Reaction of one TickIr pair on its object this tick (the thesis computes it on the haptic
/// side, §3.5; here made action = reaction):
/// the pair's rows make up Δr_i = Σ_pair f_k a_k and Δθ_i = Σ_pair f_k R_w⁻¹(r_k × a_k) of the
/// proxy offset, so the pair pushes the pointer with its share of eq. 3.7–3.8,
/// F_i = k_t Δr_i + d_t ΔΔr_i/dt and τ_i = k_r Δθ_i + d_r ΔΔθ_i/dt about the pointer origin.
/// One touched pair: the object receives −(F_i, τ_i), expressed about its COM. Several (static
/// ones included): the rendered wrench is matched by non-negative forces along the rows at the
/// penetrating points themselves, spread as a compliant contact would (min Σ λ_k²/δ_k), and each
/// object takes minus its points' forces, where they act; what the points cannot carry is shared
/// in proportion to force. Either way the sum over all pairs is exactly minus the rendered
/// wrench. A static pair's entry is zero (it takes no reaction). (The solver's own split by f_k
/// is not unique where rows are redundant, which is why several pairs are matched instead.)
struct ProxyPairReaction {
  std::uint64_t key = 0;   ///< TickPair::key
  int body = -1;           ///< TickPair::body
  bool is_static = false;  ///< TickPair::is_static (a static object takes no reaction)
  /// Force on the object (N, world) and moment about its COM p_WCm (N·m, world).
  Wrench w_W;
};

/// Counters of one tick.
struct ProxyDiagnostics {
  int contacts = 0;       ///< penetrating points = normal rows
  int rows = 0;           ///< all rows solved
  int sticking_rows = 0;  ///< friction rows in the static state
  int sliding_rows = 0;   ///< friction rows in the kinetic state
  int warm_rows = 0;      ///< rows started from the previous tick's f (same pair, point, kind)
  int iterations = 0;     ///< PGS sweeps or active-set steps used
  bool converged = true;  ///< the solver met its tolerance
  /// PGS: the last sweep's largest change of an f_k (m); active-set: the largest remaining row
  /// violation (m).
  double max_change = 0.0;
  std::uint32_t status = 0;  ///< ProxyStatusBits
};

/// Everything one tick produces. The spans point into the renderer and stay valid until its
/// next Tick or Reset.
struct ProxyOutput {
  /// Wrench on the user's hand, world frame, torque about the pointer origin (N, N·m): the sum
  /// of the contact forces (ProxyTorqueModel::kContact) or f_d and τ_d of eq. 3.7–3.8
  /// (kThesis). It pulls the pointer toward the proxy.
  Wrench w_W;
  Pose X_WQ;                       ///< proxy pose Q: {x_p + Δr, exp(Δθ) q_p} (thesis §3.2.2)
  Vec3 dr = Vec3::Zero();          ///< Δr, proxy − pointer translation (m, world)
  Vec3 dtheta = Vec3::Zero();      ///< Δθ, proxy rotation vector relative to the pointer (rad)
  std::span<const ProxyRow> rows;  ///< rows solved this tick (world)
  std::span<const ProxyRowInfo> row_info;  ///< parallel to rows
  /// Multipliers f_k (m), parallel to rows; the row's spring force is k_t f_k along a_k.
  std::span<const double> f;
  /// One entry per TickIr pair, same order (zero wrench for a pair without contact or a
  /// static one); empty after bad input.
  FixedVector<ProxyPairReaction, ir::kMaxGeometricPairs> reactions;
  ProxyDiagnostics diagnostics;
};

/// Haptic-thread half of the 6-DOF proxy method (thesis §3.2.4): from the tick's IR and pointer
/// pose it builds a normal row per penetrating point and a friction row per point that moved
/// relative to the previous proxy (eq. 3.9–3.10), solves the LCP with ProxySolver, and outputs the
/// spring–damper wrench (eq. 3.7–3.8), the proxy pose and the reactions on the objects.
///
/// Friction state across ticks. The previous proxy point of eq. 3.9 is the contact's body-fixed
/// point p_PV placed by the previous tick's proxy pose. Moving objects: each pair remembers (by
/// TickPair::key) its object pose X_WB at the previous tick, and the previous proxy pose is
/// carried with the object's pose change, X_WQ' = X_WB(t) X_WB(t−1)⁻¹ X_WQ(t−1) (the
/// "object's pose change" form, as Springhead's relative pose (the thesis assumes a static
/// object); it needs no point
/// correspondence across snapshots). First tick of a contact: if the pair had no penetrating
/// point on the previous tick (or is unknown), the previous proxy is the current pointer, s = 0,
/// and the contact starts sticking (eq. 3.9 with s = 0).
///
/// Warm start: row k starts from the previous tick's f of row k when both are the same kind of
/// row (normal / friction) of the same pair key and point index of the tick IR; otherwise from 0.
/// (Between snapshots the points are new; same-index rows then start from the old f, which only
/// affects how many steps the solve takes.)
///
/// One instance per pointer; haptic thread only. Buffers are allocated at construction.
class ProxyRenderer {
 public:
  /// @throws mrh::InvalidArgument from settings.Validate(). Not RT-safe (allocates).
  explicit ProxyRenderer(const ProxyRendererSettings& settings);

  /// Renders one haptic tick.
  /// @param ir the tick's IR evaluated at X_WP (IrInterpolator::Evaluate(alpha, X_WP, &ir)):
  ///        v_W and depth of each point must belong to X_WP.
  /// @param X_WP pointer pose (world). @param dt haptic period (s, > 0) for the dampers.
  /// @param out filled completely; see ProxyOutput.
  /// On bad input (kProxyStatusBadInput) the output is a zero wrench and the state is reset.
  /// RT-safe.
  void Tick(const TickIr& ir, const Pose& X_WP, double dt, ProxyOutput* out) noexcept;

  /// Forgets the previous proxy, Δr, Δθ, contacts and warm-start data: the next tick behaves
  /// like the first. RT-safe.
  void Reset() noexcept;

  const ProxyRendererSettings& settings() const noexcept { return settings_; }

  /// R_w⁻¹ (m⁻²).
  const Mat3& rotation_weight_inverse() const noexcept { return rotation_weight_inverse_; }

 private:
  // What a pair remembers for the next tick (matched by TickPair::key).
  struct PairMemory {
    std::uint64_t key = 0;
    Pose X_WB;
    bool in_contact = false;
    Vec3 dr_pair = Vec3::Zero();
    Vec3 dtheta_pair = Vec3::Zero();
  };

  // Identity of a row for the warm start: (pair key, point index, normal/friction) mixed into
  // one word. A collision only changes a start value, never the solution.
  using RowId = std::uint64_t;

  struct PairFrame;  // proxy_rows.cc

  void Solve(ProxyOutput* out) noexcept;
  int SweepBudget() const noexcept;
  bool InputIsFinite(const TickIr& ir, const Pose& X_WP, double dt) const noexcept;
  void CarryPreviousProxy(const TickIr& ir, const Pose& X_WP) noexcept;
  bool BuildRows(const TickIr& ir, const Pose& X_WP, ProxyDiagnostics* diag) noexcept;
  bool LoadPair(const TickIr& ir, int pair, PairFrame* frame) const noexcept;
  void ComputeReactions(const TickIr& ir, const Pose& X_WP, double dt, ProxyOutput* out) noexcept;
  void ComputeContactForces(const TickIr& ir, const Pose& X_WP, double dt,
                            ProxyOutput* out) noexcept;
  Wrench LimitedTotal(const TickIr& ir, double largest, ProxyOutput* out) noexcept;
  void AddRowForces() noexcept;
  void PushReactions(const TickIr& ir, const Pose& X_WP, ProxyOutput* out) const noexcept;
  void DistributeReactions(const TickIr& ir, const Pose& X_WP, double dt,
                           ProxyOutput* out) noexcept;
  void SplitAcrossPairs(const TickIr& ir, std::size_t touched, const ProxyOutput* out) noexcept;
  // SplitAcrossPairs' phases (proxy_reaction_split.cc).
  using PairPlanes = std::array<int, ir::kMaxGeometricPairs>;
  void LoadSplit(const TickIr& ir, PairPlanes* plane) noexcept;
  void CollectPairWrenches(const TickIr& ir, const PairPlanes& plane) noexcept;
  void SpreadRemainder(const TickIr& ir, std::size_t touched, const ProxyOutput* out) noexcept;
  void Remember(const TickIr& ir, const ProxyOutput& out) noexcept;
  void Fault(const Pose& X_WP, ProxyOutput* out) noexcept;

  ProxyRendererSettings settings_;
  Mat3 rotation_weight_inverse_;
  ProxySolver pgs_;                  // sized for max_rows only when selected
  ProxyActiveSetSolver active_set_;  // likewise
  PressureSplit split_;              // several touched pairs; warm-started tick to tick
  std::vector<int> split_row_;       // the split's row j comes from rows_[split_row_[j]]

  // This tick's rows (and the previous tick's ids and f, swapped at each tick).
  std::size_t row_count_ = 0;
  std::size_t previous_row_count_ = 0;
  std::vector<ProxyRow> rows_;
  std::vector<ProxyRowInfo> info_;
  std::vector<RowId> ids_;
  std::vector<RowId> previous_ids_;
  std::vector<double> f_;
  std::vector<double> previous_f_;

  // Per current pair: the previous proxy pose carried with its object, whether this is the
  // contact's first tick, its Δr share last tick; then what the pairs remember for next tick.
  std::array<Mat3, ir::kMaxGeometricPairs> carried_R_WQ_{};
  std::array<Vec3, ir::kMaxGeometricPairs> carried_p_WQ_{};
  std::array<bool, ir::kMaxGeometricPairs> first_tick_{};
  std::array<Vec3, ir::kMaxGeometricPairs> previous_dr_pair_{};
  std::array<Vec3, ir::kMaxGeometricPairs> previous_dtheta_pair_{};
  std::array<int, ir::kMaxGeometricPairs> pair_rows_{};     // normal rows this tick
  std::array<Vec3, ir::kMaxGeometricPairs> dr_pair_{};      // Σ_pair f_k a_k this tick
  std::array<Vec3, ir::kMaxGeometricPairs> dtheta_pair_{};  // Σ_pair f_k R_w⁻¹(r_k × a_k)
  std::array<Vec3, ir::kMaxGeometricPairs> force_pair_{};   // F_i on the pointer this tick
  std::array<Vec3, ir::kMaxGeometricPairs> torque_pair_{};  // M_i about the pointer origin
  // Contact model: the pair's friction rows' force and moment (pointer origin) and its normal
  // load this tick (N).
  std::array<Vec3, ir::kMaxGeometricPairs> friction_force_{};
  std::array<Vec3, ir::kMaxGeometricPairs> friction_torque_{};
  std::array<double, ir::kMaxGeometricPairs> normal_load_{};
  double previous_total_load_ = 0.0;  // Σ normal_load_ of the previous tick (N)
  // Per current pair: its object geom's gains (TickPair::material, else k_t, d_t, μ).
  std::array<ir::ContactGains, ir::kMaxGeometricPairs> gains_{};
  std::array<PairMemory, ir::kMaxGeometricPairs> memory_{};
  std::size_t memory_count_ = 0;

  // The previous tick's proxy.
  bool has_previous_ = false;
  Pose previous_X_WQ_;
  Vec3 previous_dr_ = Vec3::Zero();
  Vec3 previous_dtheta_ = Vec3::Zero();
};

/// Adds one tick's reactions to the period's report as impulses (thesis §3.5): for every
/// non-static body, the sum over its pairs of force · dt (N·s) and moment · dt (N·m·s, about the
/// COM); last_force of every entry becomes the body's force at this tick (zero if untouched).
/// The physics thread applies each sum / Δt^G as a constant wrench during its next step.
/// @param dt haptic period (s). RT-safe.
void AddReactionImpulses(const ProxyOutput& out, double dt, ir::HapticReport* report) noexcept;

/// The same for a bare list of per-pair reactions (penalty-sum uses it). RT-safe.
void AddReactionImpulses(const FixedVector<ProxyPairReaction, ir::kMaxGeometricPairs>& reactions,
                         double dt, ir::HapticReport* report) noexcept;

}  // namespace mrh::render
