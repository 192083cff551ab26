// SPDX-License-Identifier: Apache-2.0
// The island's world-rooted trees of hinge, slide and weld joints in joint space: which trees
// are taken, their coordinates, the joint-space mass matrix and forces of a tick, and the
// bodies' poses and twists that follow from the coordinates.
#include <bit>
#include <cmath>

#include "mrh/render/local_contact_solver.h"

namespace mrh::render {
namespace {

using ir::LocalJointType;
constexpr std::size_t kS = LocalContactSolver::kMaxTreeDofs;  // stride of the n×n matrices

// Bits of a dof mask, lowest first.
template <typename F>
void ForEachDof(std::uint32_t mask, F&& f) {
  for (; mask != 0; mask &= mask - 1) f(static_cast<std::size_t>(std::countr_zero(mask)));
}

// A⁻¹ of the symmetric positive definite n×n A (stride kS) by Cholesky; false when A is not
// positive definite.
bool InvertSpd(const double* A, std::size_t n, double* inv) {
  std::array<double, kS * kS> L{};
  for (std::size_t j = 0; j < n; ++j) {
    double s = A[j * kS + j];
    for (std::size_t k = 0; k < j; ++k) s -= L[j * kS + k] * L[j * kS + k];
    if (!(s > 0.0) || !std::isfinite(s)) return false;
    L[j * kS + j] = std::sqrt(s);
    for (std::size_t i = j + 1; i < n; ++i) {
      double t = A[i * kS + j];
      for (std::size_t k = 0; k < j; ++k) t -= L[i * kS + k] * L[j * kS + k];
      L[i * kS + j] = t / L[j * kS + j];
    }
  }
  for (std::size_t c = 0; c < n; ++c) {  // column c: L y = e_c, then Lᵀ x = y
    std::array<double, kS> y{};
    for (std::size_t i = 0; i < n; ++i) {
      double t = i == c ? 1.0 : 0.0;
      for (std::size_t k = 0; k < i; ++k) t -= L[i * kS + k] * y[k];
      y[i] = t / L[i * kS + i];
    }
    for (std::size_t i = n; i-- > 0;) {
      double t = y[i];
      for (std::size_t k = i + 1; k < n; ++k) t -= L[k * kS + i] * inv[k * kS + c];
      inv[i * kS + c] = t / L[i * kS + i];
    }
  }
  return true;
}

}  // namespace

// Takes each tree of joints rooted on the static world whose joints are hinges, slides and
// welds while the island's coordinates fit kMaxTreeDofs. A tree with a ball joint, or hanging
// from a free body, keeps its rows between maximal coordinates.
void LocalContactSolver::AdoptTrees() noexcept {
  std::array<int, ir::kMaxLocalBodies> root;
  std::array<bool, ir::kMaxLocalBodies> taken{};
  ChooseTrees(&root, &taken);
  dof_count_ = 0;
  joint_in_tree_.fill(false);
  for (std::size_t i = 0; i < joints_count_; ++i) {
    const ir::LocalJoint& j = joints_[i];
    const auto c = static_cast<std::size_t>(j.child);
    if (root[c] < 0 || !taken[static_cast<std::size_t>(root[c])]) continue;
    joint_in_tree_[i] = true;
    Body& b = bodies_[c];
    b.tree = true;
    b.parent = j.parent;
    if (b.joint < 0) b.joint = static_cast<int>(i);
    if (j.type == LocalJointType::kWeld) continue;
    dofs_[dof_count_] = TreeDof{static_cast<int>(i), j.child, j.type == LocalJointType::kSlide};
    b.dofs |= std::uint32_t{1} << dof_count_;
    ++dof_count_;
  }
  for (std::size_t i = 0; i < count_; ++i) {  // parents have lower indices
    Body& b = bodies_[i];
    if (b.tree && b.parent >= 0) b.dofs |= bodies_[static_cast<std::size_t>(b.parent)].dofs;
  }
  SetTreeState();
}

// Each jointed body's tree root (-2: a tree on a free body; -1: no joint) and which roots'
// trees are taken.
void LocalContactSolver::ChooseTrees(std::array<int, ir::kMaxLocalBodies>* root,
                                     std::array<bool, ir::kMaxLocalBodies>* taken) const noexcept {
  root->fill(-1);
  std::array<std::size_t, ir::kMaxLocalBodies> dofs{};  // per root
  std::array<bool, ir::kMaxLocalBodies> bad{};
  for (std::size_t i = 0; i < joints_count_; ++i) {  // parents first
    const ir::LocalJoint& j = joints_[i];
    const auto c = static_cast<std::size_t>(j.child);
    const int up = j.parent < 0 ? j.child : (*root)[static_cast<std::size_t>(j.parent)];
    (*root)[c] = up >= 0 ? up : -2;
    if (up < 0) continue;
    const auto r = static_cast<std::size_t>(up);
    bad[r] = bad[r] || j.type == LocalJointType::kBall;
    dofs[r] += j.type == LocalJointType::kWeld ? 0 : 1;
  }
  std::size_t total = 0;
  for (std::size_t r = 0; r < count_; ++r) {
    if ((*root)[r] != static_cast<int>(r) || bad[r] || total + dofs[r] > kMaxTreeDofs) continue;
    (*taken)[r] = true;
    total += dofs[r];
  }
}

// The coordinates and their velocities from the bodies' states.
void LocalContactSolver::SetTreeState() noexcept {
  for (std::size_t k = 0; k < dof_count_; ++k) {
    const ir::LocalJoint& j = joints_[static_cast<std::size_t>(dofs_[k].joint)];
    const JointPlacement x = PlaceJoint(j);
    const Body& C = bodies_[static_cast<std::size_t>(j.child)];
    Vec3 v = C.v + C.w.cross(x.pC - C.p), w = C.w;
    if (j.parent >= 0) {
      const Body& P = bodies_[static_cast<std::size_t>(j.parent)];
      v -= P.v + P.w.cross(x.pC - P.p);
      w -= P.w;
    }
    q_[k] = x.q;
    qd_[k] = x.axis.dot(dofs_[k].slide ? v : w);
  }
  PlaceTree();
}

// Each coordinate's axis and a point of it (world), from its parent's pose.
void LocalContactSolver::PlaceTree() noexcept {
  for (std::size_t k = 0; k < dof_count_; ++k) {
    const ir::LocalJoint& j = joints_[static_cast<std::size_t>(dofs_[k].joint)];
    Pose X_WJ = j.X_PJ;
    if (j.parent >= 0) X_WJ = X_WB(static_cast<std::size_t>(j.parent)) * j.X_PJ;
    dofs_[k].a = X_WJ.q * j.axis;
    dofs_[k].o = X_WJ.p;
  }
}

// Body b's COM twist (world) at coordinate velocities qd.
Twist LocalContactSolver::TreeTwist(const Body& b,
                                    const std::array<double, kMaxTreeDofs>& qd) const noexcept {
  Twist t;
  ForEachDof(b.dofs, [&](std::size_t k) {
    const TreeDof& d = dofs_[k];
    if (d.slide) {
      t.v += qd[k] * d.a;
    } else {
      t.w += qd[k] * d.a;
      t.v += qd[k] * d.a.cross(b.p - d.o);
    }
  });
  return t;
}

// g += sign · Jᵀ d: the coordinates' share of the velocity along d of body b's point p.
void LocalContactSolver::AddTreeJacobian(const Body& b, const Vec3& p, const Vec3& d, double sign,
                                         double* g) const noexcept {
  ForEachDof(b.dofs, [&](std::size_t k) {
    const TreeDof& f = dofs_[k];
    g[k] += sign * (f.slide ? d.dot(f.a) : d.dot(f.a.cross(p - f.o)));
  });
}

// Adds body b's inertia (mass, I_W about its COM, world) to M (Σ Jᵀ diag(m, I_W) J) and the
// generalized force of the wrench (f at its COM, tau) to Q.
void LocalContactSolver::AddBodyToTree(const Body& b, double mass, const Mat3& I_W, const Vec3& f,
                                       const Vec3& tau, double* M, double* Q) const noexcept {
  std::array<Vec3, kMaxTreeDofs> Jv, Jw;
  std::array<std::size_t, kMaxTreeDofs> idx{};
  std::size_t m = 0;
  ForEachDof(b.dofs, [&](std::size_t k) {
    const TreeDof& d = dofs_[k];
    Jv[m] = d.slide ? d.a : Vec3(d.a.cross(b.p - d.o));
    Jw[m] = d.slide ? Vec3::Zero() : d.a;
    idx[m++] = k;
  });
  for (std::size_t r = 0; r < m; ++r) {
    Q[idx[r]] += Jv[r].dot(f) + Jw[r].dot(tau);
    const Vec3 IJw = I_W * Jw[r];
    for (std::size_t c = 0; c < m; ++c) {
      M[idx[r] * kS + idx[c]] += mass * Jv[r].dot(Jv[c]) + Jw[c].dot(IJw);
    }
  }
}

// Body i's twist V[i] at qd_ and its velocity-product acceleration A[i] (COM, world: the part
// with zero coordinate accelerations), from its parent's (static: zero).
void LocalContactSolver::BiasAcceleration(
    std::size_t i, std::array<Twist, ir::kMaxLocalBodies>& V,
    std::array<Twist, ir::kMaxLocalBodies>& A) const noexcept {
  const Body& b = bodies_[i];
  V[i] = TreeTwist(b, qd_);
  Twist P, AP;
  Vec3 pP = Vec3::Zero();
  std::uint32_t own = b.dofs;
  if (b.parent >= 0) {
    const auto p = static_cast<std::size_t>(b.parent);
    P = V[p];
    AP = A[p];
    pP = bodies_[p].p;
    own &= ~bodies_[p].dofs;
  }
  A[i].w = AP.w;
  A[i].v = AP.v + AP.w.cross(b.p - pP) + P.w.cross(V[i].v - P.v);
  ForEachDof(own, [&](std::size_t k) {
    const TreeDof& d = dofs_[k];
    const Vec3 turn = qd_[k] * P.w.cross(d.a);  // the axis turning with the parent
    if (d.slide) {
      A[i].v += turn;
      return;
    }
    A[i].w += turn;
    A[i].v += turn.cross(b.p - d.o) + (qd_[k] * d.a).cross(V[i].v - P.v - P.w.cross(d.o - pP));
  });
}

// M + armature + Δt·damping (MuJoCo's Euler integrator takes damping implicitly) and the
// generalized forces: gravity, the added forces, springs, damping at the tick's start and the
// velocity-product (Coriolis, centripetal, gyroscopic) terms.
void LocalContactSolver::TreeForces(double dt, double* M, double* Q) const noexcept {
  std::array<Twist, ir::kMaxLocalBodies> V;
  std::array<Twist, ir::kMaxLocalBodies> A;
  for (std::size_t i = 0; i < count_; ++i) {
    const Body& b = bodies_[i];
    if (!b.tree) continue;
    BiasAcceleration(i, V, A);
    const double mass = b.inv_mass > 0.0 ? 1.0 / b.inv_mass : 0.0;
    const Mat3 R = b.q.toRotationMatrix();
    const Mat3 I_W = R * b.I_B * R.transpose();
    const Vec3 f = b.f + mass * (gravity_ - A[i].v);
    const Vec3 tau = b.tau - I_W * A[i].w - V[i].w.cross(I_W * V[i].w);
    AddBodyToTree(b, mass, I_W, f, tau, M, Q);
  }
  for (std::size_t k = 0; k < dof_count_; ++k) {
    const ir::LocalJoint& j = joints_[static_cast<std::size_t>(dofs_[k].joint)];
    M[k * kS + k] += j.armature + dt * j.damping;
    Q[k] -= j.stiffness * (q_[k] - j.spring_ref) + j.damping * qd_[k];
  }
}

// Minv_ = M⁻¹; a matrix that is not positive definite (a coordinate that moves no mass and has
// no armature) is regularised on its diagonal.
void LocalContactSolver::InvertTreeMass(const double* M) noexcept {
  if (InvertSpd(M, dof_count_, Minv_.data())) return;
  std::array<double, kS * kS> reg;
  std::copy(M, M + kS * kS, reg.begin());
  double trace = 0.0;
  for (std::size_t k = 0; k < dof_count_; ++k) trace += std::abs(M[k * kS + k]);
  for (std::size_t k = 0; k < dof_count_; ++k) reg[k * kS + k] += 1e-9 * trace + 1e-12;
  if (!InvertSpd(reg.data(), dof_count_, Minv_.data())) Minv_.fill(0.0);
}

// The coordinates' free velocities of this tick (semi-implicit Euler), and the tree bodies'
// twists at the tick's start and free.
void LocalContactSolver::IntegrateTree(double dt) noexcept {
  if (dof_count_ == 0) return;
  std::array<double, kS * kS> M{};
  std::array<double, kS> Q{};
  TreeForces(dt, M.data(), Q.data());
  InvertTreeMass(M.data());
  qd0_ = qd_;
  for (std::size_t k = 0; k < dof_count_; ++k) {
    double a = 0.0;
    for (std::size_t l = 0; l < dof_count_; ++l) a += Minv_[k * kS + l] * Q[l];
    qd_[k] += dt * a;
  }
  for (std::size_t i = 0; i < count_; ++i) {
    Body& b = bodies_[i];
    if (!b.tree) continue;
    const Twist t0 = TreeTwist(b, qd0_), t = TreeTwist(b, qd_);
    b.v0 = t0.v;
    b.w0 = t0.w;
    b.v = t.v;
    b.w = t.w;
  }
}

// Coordinates from the constrained velocities, then the bodies' poses (parents first) and
// twists. A non-finite velocity stops the tree where it is.
bool LocalContactSolver::FinishTree(double dt) noexcept {
  if (dof_count_ == 0) return true;
  bool finite = true;
  for (std::size_t k = 0; k < dof_count_; ++k) finite = finite && std::isfinite(qd_[k]);
  if (!finite) qd_.fill(0.0);
  for (std::size_t k = 0; k < dof_count_; ++k) q_[k] += dt * qd_[k];
  for (std::size_t i = 0; i < count_; ++i) {
    Body& b = bodies_[i];
    if (!b.tree) continue;
    const ir::LocalJoint& j = joints_[static_cast<std::size_t>(b.joint)];
    const Pose X_WP = b.parent >= 0 ? X_WB(static_cast<std::size_t>(b.parent)) : Pose{};
    Pose X_WJ = X_WP * j.X_PJ;
    const std::uint32_t own =
        b.parent >= 0 ? b.dofs & ~bodies_[static_cast<std::size_t>(b.parent)].dofs : b.dofs;
    if (j.type == LocalJointType::kHinge) {
      const std::size_t k = static_cast<std::size_t>(std::countr_zero(own));
      X_WJ.q = X_WJ.q * Quat(Eigen::AngleAxisd(q_[k] - j.qpos0, j.axis));
    }
    Pose X_WC = X_WJ * j.X_CJ.Inverse();
    if (j.type == LocalJointType::kSlide) {
      ForEachDof(own, [&](std::size_t k) {
        const ir::LocalJoint& s = joints_[static_cast<std::size_t>(dofs_[k].joint)];
        X_WC.p += (q_[k] - s.qpos0) * (X_WP.q * (s.X_PJ.q * s.axis));
      });
    }
    b.q = X_WC.q.normalized();
    b.p = X_WC * b.p_BCm;
  }
  PlaceTree();
  for (std::size_t i = 0; i < count_; ++i) {
    Body& b = bodies_[i];
    if (!b.tree) continue;
    const Twist t = TreeTwist(b, qd_);
    b.v = t.v;
    b.w = t.w;
  }
  return finite;
}

}  // namespace mrh::render
