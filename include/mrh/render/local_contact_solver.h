// SPDX-License-Identifier: Apache-2.0
// The contact local model of local-dynamics: the neighbors' contact island simulated
// at the haptic rate with its own contacts (normal + Coulomb friction cone) under gravity.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "mrh/core/spatial.h"
#include "mrh/ir/local_contact.h"

namespace mrh::render {

/// Settings of the local contact solve.
struct LocalContactSolverSettings {
  int iterations = 30;  ///< projected Gauss–Seidel sweeps per tick at most (>= 1)
  /// Stop when no sweep changed a contact's relative velocity by more than this (m/s): an
  /// impulse change over the row's effective mass. 1e-6 m/s is 1 nm of motion per tick.
  double tolerance = 1e-6;
  /// Share of a penetration deeper than the exported one removed per tick (velocity-level
  /// Baumgarte term, dimensionless, 0..1).
  double baumgarte = 0.1;
  /// true: penetrating contacts are MuJoCo's soft constraints (the rows' solref/solimp:
  /// impedance, regularisation R = (1 − d)/d · (1/m_A + 1/m_B), reference acceleration
  /// −b v − k d r), as in the single-rate reference; open contacts stay hard and speculative.
  /// false: hard contacts holding the exported resting depth, Baumgarte above it.
  bool soft_contacts = true;
};

/// The island of ir::LocalContactModel as a small rigid-body simulation: per tick, semi-implicit
/// Euler with gravity, joint springs, the forces added by AddForce() (the pointer's reaction,
/// eq. 4.12), the island's joints (ir::LocalJoint: a world-rooted tree of hinges, slides and
/// welds in its joint coordinates, see kMaxTreeDofs; other joints as rows between maximal
/// coordinates: bilateral position rows with a Baumgarte term, implicit damping, armature; both
/// with dry friction and soft limits on the joint coordinate) and the
/// contact impulses of a projected Gauss–Seidel solve of the island's contact rows (velocity
/// level: non-penetration with a speculative term for open contacts, λ_n >= 0, friction in the
/// scene's cone — MuJoCo's pyramid |λ_t1| + |λ_t2| <= μ λ_n about the contact frame, or the
/// elliptic disc |λ_t| <= μ λ_n (ir::LocalContactRow::pyramidal) — warm-started from the
/// previous tick). Contacts open and close with the
/// gap of body-fixed points; stick and slip follow from the cone. State: COM position, unit
/// quaternion (body → world), COM twist, world frame. Fixed capacity, no allocation; every
/// member is RT-safe (haptic thread only).
class LocalContactSolver {
 public:
  /// Joint space: a tree of hinge, slide and weld joints rooted on the static world is
  /// simulated in its joint coordinates (MuJoCo's own) with the joint-space mass matrix, while
  /// the island's coordinates fit this many; the other joints (ball joints, trees on a free
  /// body, trees beyond the capacity) are rows between maximal coordinates.
  static constexpr std::size_t kMaxTreeDofs = 16;

  explicit LocalContactSolver(const LocalContactSolverSettings& settings = {}) noexcept
      : settings_(settings) {}

  /// Takes a new period's model. A body that was in the current model (same world id, not
  /// flagged reset) keeps its local state (the local simulation owns it while it stays in the
  /// island); the others start from the exported state. A reset body that was pushed
  /// (AddForce) since the latest Adopt keeps its local state too: the snapshot was exported
  /// before that push reached the world, and the next synchronization writes it. RT-safe.
  void Adopt(const ir::LocalContactModel& model) noexcept;

  /// As Adopt, but every body starts from the model's exported state, none from a local state:
  /// for a caller whose world owns the bodies' state every period (proxy-6dof's physics-side
  /// island, rebuilt from the world each step). The contacts are still warm-started from the
  /// latest rows' impulses: a projected Gauss–Seidel solve cut at `iterations` sweeps from zero
  /// impulses leaves a sliding, turning body's friction loads unresolved. RT-safe.
  void Restart(const ir::LocalContactModel& model) noexcept;

  /// Drops every body (e.g. a method that stopped using the model). RT-safe.
  void Clear() noexcept {
    count_ = 0;
    rows_count_ = 0;
    joints_count_ = 0;
    jrows_count_ = 0;
    dof_count_ = 0;
    dof_rows_count_ = 0;
  }

  std::size_t size() const noexcept { return count_; }

  /// Local index of the body with snapshot motion index `motion`, or -1. RT-safe.
  int FindMotion(int motion) const noexcept;

  int world_body(std::size_t i) const noexcept { return bodies_[i].body; }

  /// Body pose, COM and COM twist of local body i (world). RT-safe.
  Pose X_WB(std::size_t i) const noexcept;

  const Vec3& p_WCm(std::size_t i) const noexcept { return bodies_[i].p; }

  Twist V_WCm(std::size_t i) const noexcept { return Twist{bodies_[i].v, bodies_[i].w}; }

  /// Velocity of local body i's material point at p_W (world). RT-safe.
  Vec3 PointVelocity(std::size_t i, const Vec3& p_W) const noexcept {
    return bodies_[i].v + bodies_[i].w.cross(p_W - bodies_[i].p);
  }

  /// Adds force f_W (N, world) at p_W (m, world) on local body i for the next Step(). RT-safe.
  void AddForce(std::size_t i, const Vec3& f_W, const Vec3& p_W) noexcept;

  /// Adds a pure moment tau_W (N·m, world) on local body i for the next Step(). RT-safe.
  void AddTorque(std::size_t i, const Vec3& tau_W) noexcept {
    bodies_[i].pushed = true;
    bodies_[i].tau += tau_W;
  }

  /// Advances one tick of dt (s). Returns false if a state became non-finite: that body is
  /// then kept at its pose with zero twist. RT-safe.
  [[nodiscard]] bool Step(double dt) noexcept;

  /// Joint coordinate of the island's joint j at the local poses (hinge rad, slide m; ball and
  /// weld 0), as MuJoCo's qpos would read. RT-safe.
  double JointPosition(std::size_t j) const noexcept;

  std::size_t joint_count() const noexcept { return joints_count_; }

  /// Joint coordinates the latest Adopt() or Restart() put in joint space (see kMaxTreeDofs; the
  /// island's other joints are rows). RT-safe.
  std::size_t tree_dof_count() const noexcept { return dof_count_; }

  /// Contact rows that carried a normal impulse in the latest Step(). RT-safe.
  int active_contacts() const noexcept { return active_; }

  /// Gauss–Seidel sweeps done in the latest Step() (diagnostics, benchmark). RT-safe.
  int last_sweeps() const noexcept { return sweeps_; }

 private:
  struct Body {
    int body = -1;
    int motion = -1;
    Vec3 p = Vec3::Zero();  // COM (world)
    Quat q = Quat::Identity();
    Vec3 p_BCm = Vec3::Zero();
    Vec3 v = Vec3::Zero();
    Vec3 w = Vec3::Zero();
    Vec3 v0 = Vec3::Zero();  // this tick's start (before Integrate)
    Vec3 w0 = Vec3::Zero();
    double inv_mass = 0.0;
    double inv_weight = 0.0;  // soft contacts' regularisation (ir::LocalIslandBody::inv_weight)
    Mat3 I_B = Mat3::Zero();
    Mat3 I_B_inv = Mat3::Zero();
    Mat3 I_W_inv = Mat3::Zero();  // this tick
    Vec3 f = Vec3::Zero();        // accumulated this tick
    Vec3 tau = Vec3::Zero();      // about the COM
    bool pushed = false;          // AddForce was called since the latest Adopt
    // Joint space: the body is in a tree solved in its coordinates (AdoptTrees); its pose and
    // twist follow from them. dofs: bit k set when tree dof k moves it; joint: its first joint.
    bool tree = false;
    std::uint32_t dofs = 0;
    int joint = -1;
    int parent = -1;  // island index, -1: static
  };

  struct Row {
    ir::LocalContactRow c;
    // This tick: world normal and tangents, lever arms, inverse effective masses, target.
    std::array<Vec3, 3> d{};
    Vec3 rA = Vec3::Zero();
    Vec3 rB = Vec3::Zero();
    std::array<double, 3> inv_w{};   // 1 / (A_jj + R): A_jj the row's inverse effective mass
    std::array<double, 3> target{};  // velocity (m/s) the row drives to (less R λ when soft)
    double R = 0.0;                  // soft regularisation (1/kg; 0: hard)
    double a12 = 0.0;  // the friction rows' coupling d1·(A d2) in A (1/kg): the disc's block
    // The disc's block M = A_tt + R I (kg): its diagonal 1 / inv_w[1], 1 / inv_w[2] (0 where
    // inv_w is 0) and determinant m11 m22 − a12², which every sweep of the tick uses.
    double m11 = 0.0;
    double m22 = 0.0;
    double det = 0.0;
    double hold = 0.0;  // penetration kept, not pushed out (m, >= 0; HoldRestingPenetration)
    std::array<double, 3> lambda{};  // impulses (N·s): normal, t1, t2
    // Per direction j, this tick: the angular Jacobians r × d_j and the angular velocity
    // changes per unit impulse I_W⁻¹ (r × d_j) of A and B, so that a sweep's velocity and
    // impulse updates are dot products and additions.
    std::array<Vec3, 3> jA{};
    std::array<Vec3, 3> mA{};
    std::array<Vec3, 3> jB{};
    std::array<Vec3, 3> mB{};
    // A side in a joint-space tree moves through the tree's coordinates, not its body twist:
    // the row's Jacobian over them is tree_rows_[tree] (-1: neither side is in a tree).
    bool a_tree = false;
    bool b_tree = false;
    int tree = -1;
  };

  // One coordinate of a tree: joint `joint` (hinge or slide) of body `body`; its axis a and a
  // point o of it (world) at this tick's poses.
  struct TreeDof {
    int joint = -1;
    int body = -1;
    bool slide = false;
    Vec3 a = Vec3::UnitZ();
    Vec3 o = Vec3::Zero();
  };

  // A contact row's generalized Jacobian g over the tree coordinates and h = M⁻¹ g, per
  // direction.
  struct TreeRow {
    std::array<std::array<double, kMaxTreeDofs>, 3> g{};
    std::array<std::array<double, kMaxTreeDofs>, 3> h{};
  };

  // A row on one tree coordinate (dry friction or a limit): velocity sign·q̇[dof].
  struct DofRow {
    int dof = 0;
    int slot = 0;  // joint_lambda_ slot
    double sign = 1.0;
    double inv_w = 0.0;
    double target = 0.0;
    double R = 0.0;
    double lo = 0.0;
    double hi = 0.0;
  };

  // One scalar row of a joint: relative velocity d·(v_A − v_B) + jA·ω_A − jB·ω_B of child A
  // over parent B (static when b < 0); d is zero for an angular row. λ lives in joint_lambda_
  // [slot] (warm start across ticks and periods), bounded by [lo, hi].
  struct JointRow {
    int a = -1;
    int b = -1;
    int slot = 0;
    Vec3 d = Vec3::Zero();
    Vec3 jA = Vec3::Zero();
    Vec3 jB = Vec3::Zero();
    Vec3 mA = Vec3::Zero();  // I_A⁻¹ jA
    Vec3 mB = Vec3::Zero();
    double inv_w = 0.0;  // 1 / (A_jj + R)
    double target = 0.0;
    double R = 0.0;
    double lo = 0.0;
    double hi = 0.0;
  };

  // A joint's frames and coordinate at this tick's poses (world).
  struct JointPlacement {
    Vec3 pC = Vec3::Zero();       // anchor on the child
    Vec3 pP = Vec3::Zero();       // anchor on the parent
    Quat qC = Quat::Identity();   // child's copy of the joint frame
    Quat qP = Quat::Identity();   // parent's copy
    Vec3 axis = Vec3::UnitZ();    // the parent's copy of the axis
    Quat rel = Quat::Identity();  // qP⁻¹ qC, w >= 0
    double q = 0.0;               // hinge angle or slide position, qpos units
  };

  // Rows one joint may take: 3 linear, 3 angular, 3 damping, 3 armature, 3 friction, 2 limits;
  // its slots in joint_lambda_ start at joint · kJointSlots, each kind at its k…Slot.
  static constexpr std::size_t kJointSlots = 17;
  static constexpr int kLinearSlot = 0;
  static constexpr int kAngularSlot = 3;
  static constexpr int kDampingSlot = 6;
  static constexpr int kArmatureSlot = 9;
  static constexpr int kFrictionSlot = 12;
  static constexpr int kLimitSlot = 15;

  // A previous period's row impulses, kept to warm-start the same contact in the next period.
  struct WarmRow {
    int a_body = -1;
    int b_body = -1;
    Vec3 p_A = Vec3::Zero();
    std::array<double, 3> lambda{};
  };

  void AdoptModel(const ir::LocalContactModel& model, bool keep_local_state) noexcept;
  void AdoptBodies(const ir::LocalContactModel& model, std::size_t n,
                   bool keep_local_state) noexcept;
  void SaveWarmStart() noexcept;
  void WarmStart(Row& r, std::size_t k) const noexcept;
  void HoldRestingPenetration() noexcept;
  void Integrate(double dt) noexcept;
  void PrepareRows(double dt) noexcept;
  void PrepareRow(Row& r, double dt) noexcept;
  void PlaceContact(Row& r, Vec3* pA, Vec3* pB, Vec3* n, Vec3* t) const noexcept;
  void PlaceB(Row& r, Vec3* pB, Vec3* n, Vec3* t) const noexcept;
  void SetDirections(Row& r, const Vec3& n, const Vec3& t) noexcept;
  void SetTargets(Row& r, double gap, double dt) const noexcept;
  double RelativeStartVelocity(const Row& r, const Vec3& dir) const noexcept;
  // The impulse change dl (N·s) along the row's direction j applied to A and, opposite, B.
  void ApplyImpulse(Row& r, int j, double dl) noexcept;
  // The relative velocity (m/s) of A's contact point over B's along direction j.
  double RelativeVelocity(const Row& r, int j) const noexcept;
  double SolveRow(Row& r, bool reverse) noexcept;
  double SolveFrictionBox(Row& r, double limit, bool reverse) noexcept;
  bool Finish(double dt) noexcept;
  void AdoptJoints(const ir::LocalContactModel& model) noexcept;
  JointPlacement PlaceJoint(const ir::LocalJoint& j) const noexcept;
  void PlaceJoints() noexcept;
  void AddJointSprings() noexcept;
  void PrepareJointRows(double dt) noexcept;
  void AddPositionRows(const ir::LocalJoint& j, const JointPlacement& x, int base,
                       double dt) noexcept;
  int SlideCrossDirections(int i, const JointPlacement& x, Vec3* t) const noexcept;
  void AddDofRows(const ir::LocalJoint& j, const JointPlacement& x, int base, double dt) noexcept;
  void AddLimitRows(const ir::LocalJoint& j, const JointPlacement& x, int base, double dt) noexcept;
  JointRow& AddLinearRow(const ir::LocalJoint& j, int slot, const Vec3& d, const Vec3& p_A,
                         const Vec3& p_B) noexcept;
  JointRow& AddAngularRow(const ir::LocalJoint& j, int slot, const Vec3& e) noexcept;
  void FinishJointRow(JointRow& r, double R) noexcept;
  double JointRowVelocity(const JointRow& r, bool start) const noexcept;
  void ApplyJointImpulse(JointRow& r, double dl) noexcept;
  double SolveJointRow(JointRow& r) noexcept;
  void AdoptTrees() noexcept;
  void ChooseTrees(std::array<int, ir::kMaxLocalBodies>* root,
                   std::array<bool, ir::kMaxLocalBodies>* taken) const noexcept;
  void BiasAcceleration(std::size_t i, std::array<Twist, ir::kMaxLocalBodies>& V,
                        std::array<Twist, ir::kMaxLocalBodies>& A) const noexcept;
  void SetTreeState() noexcept;
  void PlaceTree() noexcept;
  Twist TreeTwist(const Body& b, const std::array<double, kMaxTreeDofs>& qd) const noexcept;
  void AddTreeJacobian(const Body& b, const Vec3& p, const Vec3& d, double sign,
                       double* g) const noexcept;
  void IntegrateTree(double dt) noexcept;
  void TreeForces(double dt, double* M, double* Q) const noexcept;
  void AddBodyToTree(const Body& b, double mass, const Mat3& I_W, const Vec3& f, const Vec3& tau,
                     double* M, double* Q) const noexcept;
  void InvertTreeMass(const double* M) noexcept;
  void ApplyTree(const std::array<double, kMaxTreeDofs>& h, double dl) noexcept;
  double TreeVelocity(const std::array<double, kMaxTreeDofs>& g) const noexcept;
  void SetTreeRow(Row& r) noexcept;
  void PrepareDofRows(double dt) noexcept;
  DofRow& AddDofRow(std::size_t dof, int slot, double sign) noexcept;
  void ApplyDof(const DofRow& r, double dl) noexcept;
  double SolveDofRow(DofRow& r) noexcept;
  double SolveDofRows(bool forward) noexcept;
  bool FinishTree(double dt) noexcept;

  LocalContactSolverSettings settings_;
  std::array<Body, ir::kMaxLocalBodies> bodies_{};
  std::array<Body, ir::kMaxLocalBodies> scratch_{};
  std::size_t count_ = 0;
  std::array<Row, ir::kMaxLocalContacts> rows_{};
  std::size_t rows_count_ = 0;
  std::array<WarmRow, ir::kMaxLocalContacts> warm_{};
  std::size_t warm_count_ = 0;
  std::array<ir::LocalJoint, ir::kMaxLocalJoints> joints_{};
  std::size_t joints_count_ = 0;
  std::array<JointPlacement, ir::kMaxLocalJoints> placements_{};  // this tick (PlaceJoints)
  std::array<JointRow, ir::kMaxLocalJoints * kJointSlots> jrows_{};
  std::size_t jrows_count_ = 0;
  std::array<double, ir::kMaxLocalJoints * kJointSlots> joint_lambda_{};
  std::array<bool, ir::kMaxLocalJoints> joint_in_tree_{};
  std::array<TreeDof, kMaxTreeDofs> dofs_{};
  std::size_t dof_count_ = 0;
  std::array<double, kMaxTreeDofs> q_{};                    // coordinates (qpos units)
  std::array<double, kMaxTreeDofs> qd_{};                   // their velocities
  std::array<double, kMaxTreeDofs> qd0_{};                  // at this tick's start
  std::array<double, kMaxTreeDofs * kMaxTreeDofs> Minv_{};  // (M + armature + Δt D)⁻¹, this tick
  std::array<TreeRow, ir::kMaxLocalContacts> tree_rows_{};
  std::size_t tree_rows_count_ = 0;
  std::array<DofRow, 3 * kMaxTreeDofs> dof_rows_{};
  std::size_t dof_rows_count_ = 0;
  int sweeps_ = 0;
  Vec3 gravity_ = Vec3::Zero();
  int active_ = 0;
};

}  // namespace mrh::render
