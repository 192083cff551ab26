// SPDX-License-Identifier: Apache-2.0
// The joints of the contact local model's island as rows between maximal coordinates: the
// joint's position rows, its coordinate's damping, armature, dry friction and limits, and its
// spring as an explicit force.
#include <cmath>
#include <limits>

#include "mrh/render/local_contact_solver.h"
#include "soft_constraint.h"

namespace mrh::render {
namespace {

using ir::LocalJointType;

// Share of a joint's position error removed per tick (velocity-level Baumgarte term): at 1 kHz
// an error decays with a 50 ms time constant. The bias acts as a stiff spring on the joint
// error; at 0.1 or more per tick it fed the pointer's 33 Hz oscillation on the d2 lamp until it
// diverged, while 0.01–0.05 give the same d2 results.
constexpr double kJointBaumgarte = 0.02;
constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

// Takes the model's joints. A joint at the same index joining the same two world bodies keeps
// its impulses (the rows of a period start from the last period's loads).
void LocalContactSolver::AdoptJoints(const ir::LocalContactModel& model) noexcept {
  const std::size_t n = std::min(model.joints.size(), joints_.size());
  for (std::size_t i = 0; i < n; ++i) {
    const ir::LocalJoint& j = model.joints[i];
    const bool same = i < joints_count_ && joints_[i].joint == j.joint &&
                      joints_[i].type == j.type && joints_[i].child >= 0 && j.child >= 0;
    if (!same) {
      for (std::size_t s = 0; s < kJointSlots; ++s) joint_lambda_[i * kJointSlots + s] = 0.0;
    }
    joints_[i] = j;
  }
  joints_count_ = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const ir::LocalJoint& j = joints_[i];
    const bool valid = j.child >= 0 && static_cast<std::size_t>(j.child) < count_ &&
                       j.parent < static_cast<int>(count_) && j.parent != j.child;
    if (!valid) break;  // a joint the bodies do not hold ends the list (capacity)
    ++joints_count_;
  }
  jrows_count_ = 0;
}

LocalContactSolver::JointPlacement LocalContactSolver::PlaceJoint(
    const ir::LocalJoint& j) const noexcept {
  JointPlacement x;
  const Body& C = bodies_[static_cast<std::size_t>(j.child)];
  x.pC = C.p + C.q * (j.X_CJ.p - C.p_BCm);
  x.qC = C.q * j.X_CJ.q;
  if (j.parent >= 0) {
    const Body& P = bodies_[static_cast<std::size_t>(j.parent)];
    x.pP = P.p + P.q * (j.X_PJ.p - P.p_BCm);
    x.qP = P.q * j.X_PJ.q;
  } else {
    x.pP = j.X_PJ.p;
    x.qP = j.X_PJ.q;
  }
  x.axis = x.qP * j.axis;
  x.rel = (x.qP.conjugate() * x.qC).normalized();
  if (x.rel.w() < 0.0) x.rel.coeffs() *= -1.0;
  if (j.type == LocalJointType::kHinge) {
    x.q = j.qpos0 + 2.0 * std::atan2(x.rel.vec().dot(j.axis), x.rel.w());
  } else if (j.type == LocalJointType::kSlide) {
    x.q = j.qpos0 + x.axis.dot(x.pC - x.pP);
  }
  return x;
}

double LocalContactSolver::JointPosition(std::size_t j) const noexcept {
  return PlaceJoint(joints_[j]).q;
}

// Every row joint's placement at this tick's poses, for the springs and the rows (positions
// change only in Finish, after both); joint-space trees use their coordinates instead.
void LocalContactSolver::PlaceJoints() noexcept {
  for (std::size_t i = 0; i < joints_count_; ++i) {
    if (!joint_in_tree_[i]) placements_[i] = PlaceJoint(joints_[i]);
  }
}

// Joint springs, explicit as MuJoCo's passive forces: −k (q − spring_ref) on the coordinate (a
// ball: −k times the rotation vector from the spring orientation, in the joint frame).
void LocalContactSolver::AddJointSprings() noexcept {
  for (std::size_t i = 0; i < joints_count_; ++i) {
    const ir::LocalJoint& j = joints_[i];
    if (!(j.stiffness > 0.0) || j.type == LocalJointType::kWeld || joint_in_tree_[i]) continue;
    const JointPlacement& x = placements_[i];
    Body& C = bodies_[static_cast<std::size_t>(j.child)];
    Body* P = j.parent >= 0 ? &bodies_[static_cast<std::size_t>(j.parent)] : nullptr;
    if (j.type == LocalJointType::kSlide) {
      const Vec3 f = -j.stiffness * (x.q - j.spring_ref) * x.axis;
      C.f += f;
      C.tau += (x.pC - C.p).cross(f);
      if (P != nullptr) {
        P->f -= f;
        P->tau -= (x.pC - P->p).cross(f);
      }
      continue;
    }
    const Vec3 tau =
        j.type == LocalJointType::kHinge
            ? Vec3(-j.stiffness * (x.q - j.spring_ref) * x.axis)
            : Vec3(x.qC * (-j.stiffness * RotationVectorFromQuat(j.spring_q.conjugate() * x.rel)));
    C.tau += tau;
    if (P != nullptr) P->tau -= tau;
  }
}

// Every joint's rows of this tick, warm-started with their impulses of the last tick.
void LocalContactSolver::PrepareJointRows(double dt) noexcept {
  jrows_count_ = 0;
  for (std::size_t i = 0; i < joints_count_; ++i) {
    if (joint_in_tree_[i]) continue;  // joint space: IntegrateTree, PrepareDofRows
    const ir::LocalJoint& j = joints_[i];
    const JointPlacement& x = placements_[i];
    const int base = static_cast<int>(i * kJointSlots);
    AddPositionRows(j, x, base, dt);
    if (j.type != LocalJointType::kWeld) AddDofRows(j, x, base, dt);
    if (j.limited && (j.type == LocalJointType::kHinge || j.type == LocalJointType::kSlide)) {
      AddLimitRows(j, x, base, dt);
    }
  }
  for (std::size_t k = 0; k < jrows_count_; ++k) {
    JointRow& r = jrows_[k];
    const double l = joint_lambda_[static_cast<std::size_t>(r.slot)];
    if (l != 0.0) ApplyJointImpulse(r, l);
  }
}

// The directions across slide joint i's axis that its body may not translate along (t, up to
// two; returned: how many). A translating body's slides are consecutive joints of one child:
// the first takes the directions across all their axes (2, 1 or 0 for one, two or three
// slides); a later one returns -1.
int LocalContactSolver::SlideCrossDirections(int i, const JointPlacement& x,
                                             Vec3* t) const noexcept {
  const auto n = static_cast<std::size_t>(i);
  const ir::LocalJoint& j = joints_[n];
  const auto same_body = [&](std::size_t k) {
    return joints_[k].child == j.child && joints_[k].type == LocalJointType::kSlide;
  };
  if (n > 0 && same_body(n - 1)) return -1;
  std::size_t count = 1;
  while (n + count < joints_count_ && same_body(n + count) && count < 3) ++count;
  if (count == 1) {
    internal::Tangents(x.axis, &t[0], &t[1]);
    return 2;
  }
  if (count == 3) return 0;
  t[0] = x.axis.cross(x.qP * joints_[n + 1].axis).normalized();
  return 1;
}

// The bilateral rows that hold the two copies of the joint frame together where the joint does
// not let them move, each driven to remove kJointBaumgarte of its error per tick.
void LocalContactSolver::AddPositionRows(const ir::LocalJoint& j, const JointPlacement& x, int base,
                                         double dt) noexcept {
  const double gain = kJointBaumgarte / dt;
  if (j.type == LocalJointType::kSlide) {
    Vec3 t[2];
    const int across = SlideCrossDirections(base / static_cast<int>(kJointSlots), x, t);
    if (across < 0) return;  // a translating body's later slide: its first one holds the body
    const Vec3 e = x.pC - x.pP;
    for (int k = 0; k < across; ++k) {
      JointRow& r = AddLinearRow(j, base + kLinearSlot + k, t[k], x.pC, x.pC);
      r.target = -gain * t[k].dot(e);
      FinishJointRow(r, 0.0);
    }
  } else {
    const Vec3 e = x.pC - x.pP;
    for (int k = 0; k < 3; ++k) {
      JointRow& r = AddLinearRow(j, base + kLinearSlot + k, Vec3::Unit(k), x.pC, x.pP);
      r.target = -gain * e[k];
      FinishJointRow(r, 0.0);
    }
  }
  if (j.type == LocalJointType::kBall) return;
  if (j.type == LocalJointType::kHinge) {
    const Vec3 phi = x.axis.cross(x.qC * j.axis);  // the child's axis turned off the parent's
    Vec3 t[2];
    internal::Tangents(x.axis, &t[0], &t[1]);
    for (int k = 0; k < 2; ++k) {
      JointRow& r = AddAngularRow(j, base + kAngularSlot + k, t[k]);
      r.target = -gain * t[k].dot(phi);
      FinishJointRow(r, 0.0);
    }
    return;
  }
  const Vec3 phi = x.qP * RotationVectorFromQuat(x.rel);  // slide, weld: no relative rotation
  for (int k = 0; k < 3; ++k) {
    JointRow& r = AddAngularRow(j, base + kAngularSlot + k, Vec3::Unit(k));
    r.target = -gain * phi[k];
    FinishJointRow(r, 0.0);
  }
}

// The coordinate's damping (implicit, as MuJoCo's Euler integrator: R = 1 / (d Δt) makes the
// row's impulse −d Δt v at the new velocity), armature (R = 1 / armature toward the tick's start
// velocity: the impulse −armature Δv) and dry friction (MuJoCo's soft friction-loss row, its
// impulse within ±frictionloss Δt). A ball's three coordinates turn about the joint frame's axes.
void LocalContactSolver::AddDofRows(const ir::LocalJoint& j, const JointPlacement& x, int base,
                                    double dt) noexcept {
  const int dofs = j.type == LocalJointType::kBall ? 3 : 1;
  for (int k = 0; k < dofs; ++k) {
    const auto add = [&](int slot) -> JointRow& {
      if (j.type == LocalJointType::kSlide) return AddLinearRow(j, slot, x.axis, x.pC, x.pC);
      return AddAngularRow(j, slot,
                           j.type == LocalJointType::kBall ? Vec3(x.qC * Vec3::Unit(k)) : x.axis);
    };
    if (j.damping > 0.0) FinishJointRow(add(base + kDampingSlot + k), 1.0 / (j.damping * dt));
    if (j.armature > 0.0) {
      JointRow& r = add(base + kArmatureSlot + k);
      r.target = JointRowVelocity(r, true);
      FinishJointRow(r, 1.0 / j.armature);
    }
    if (j.frictionloss > 0.0) {
      JointRow& r = add(base + kFrictionSlot + k);
      const internal::SoftRow s = internal::FrictionLossRow(j.solref_friction, j.solimp_friction,
                                                            dt, JointRowVelocity(r, true), r.inv_w);
      r.target = s.target;
      r.lo = -j.frictionloss * dt;
      r.hi = j.frictionloss * dt;
      FinishJointRow(r, s.R);
    }
  }
}

// The range's two ends as unilateral rows on the coordinate, like the contacts' normals: hard
// and speculative while the coordinate is inside (range − margin), MuJoCo's soft limit (solref,
// solimp of the limit) beyond.
void LocalContactSolver::AddLimitRows(const ir::LocalJoint& j, const JointPlacement& x, int base,
                                      double dt) noexcept {
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    const double gap = sign * (x.q - j.range[side]) - j.margin;
    const Vec3 dir = sign * x.axis;
    JointRow& r = j.type == LocalJointType::kSlide
                      ? AddLinearRow(j, base + kLimitSlot + side, dir, x.pC, x.pC)
                      : AddAngularRow(j, base + kLimitSlot + side, dir);
    r.lo = 0.0;
    r.hi = kInf;
    const internal::SoftRow s = internal::LimitRow(j.solref_limit, j.solimp_limit, dt, gap,
                                                   JointRowVelocity(r, true), r.inv_w);
    r.target = s.target;
    FinishJointRow(r, s.R);
  }
}

// A row along d through the child's point p_A and the parent's point p_B (world); unbounded.
// r.inv_w holds A_jj until FinishJointRow.
LocalContactSolver::JointRow& LocalContactSolver::AddLinearRow(const ir::LocalJoint& j, int slot,
                                                               const Vec3& d, const Vec3& p_A,
                                                               const Vec3& p_B) noexcept {
  JointRow& r = AddAngularRow(j, slot, Vec3::Zero());
  const Body& A = bodies_[static_cast<std::size_t>(r.a)];
  r.d = d;
  r.jA = (p_A - A.p).cross(d);
  r.mA = A.I_W_inv * r.jA;
  r.inv_w = A.inv_mass + r.jA.dot(r.mA);
  if (r.b >= 0) {
    const Body& B = bodies_[static_cast<std::size_t>(r.b)];
    r.jB = (p_B - B.p).cross(d);
    r.mB = B.I_W_inv * r.jB;
    r.inv_w += B.inv_mass + r.jB.dot(r.mB);
  }
  return r;
}

// A row on the relative angular velocity about the unit axis e (world); unbounded.
LocalContactSolver::JointRow& LocalContactSolver::AddAngularRow(const ir::LocalJoint& j, int slot,
                                                                const Vec3& e) noexcept {
  JointRow& r = jrows_[jrows_count_++];
  r = JointRow{};
  r.a = j.child;
  r.b = j.parent;
  r.slot = slot;
  r.lo = -kInf;
  r.hi = kInf;
  const Body& A = bodies_[static_cast<std::size_t>(r.a)];
  r.jA = e;
  r.mA = A.I_W_inv * e;
  r.inv_w = e.dot(r.mA);
  if (r.b >= 0) {
    const Body& B = bodies_[static_cast<std::size_t>(r.b)];
    r.jB = e;
    r.mB = B.I_W_inv * e;
    r.inv_w += e.dot(r.mB);
  }
  return r;
}

void LocalContactSolver::FinishJointRow(JointRow& r, double R) noexcept {
  r.R = R;
  r.inv_w = r.inv_w + R > 0.0 ? 1.0 / (r.inv_w + R) : 0.0;
}

double LocalContactSolver::JointRowVelocity(const JointRow& r, bool start) const noexcept {
  const Body& A = bodies_[static_cast<std::size_t>(r.a)];
  double v = r.d.dot(start ? A.v0 : A.v) + r.jA.dot(start ? A.w0 : A.w);
  if (r.b >= 0) {
    const Body& B = bodies_[static_cast<std::size_t>(r.b)];
    v -= r.d.dot(start ? B.v0 : B.v) + r.jB.dot(start ? B.w0 : B.w);
  }
  return v;
}

void LocalContactSolver::ApplyJointImpulse(JointRow& r, double dl) noexcept {
  Body& A = bodies_[static_cast<std::size_t>(r.a)];
  A.v += (A.inv_mass * dl) * r.d;
  A.w += dl * r.mA;
  if (r.b >= 0) {
    Body& B = bodies_[static_cast<std::size_t>(r.b)];
    B.v -= (B.inv_mass * dl) * r.d;
    B.w -= dl * r.mB;
  }
}

// One Gauss–Seidel update of a joint row; returns the change of its relative velocity (m/s or
// rad/s).
double LocalContactSolver::SolveJointRow(JointRow& r) noexcept {
  double& l = joint_lambda_[static_cast<std::size_t>(r.slot)];
  const double next =
      internal::RowUpdate(l, JointRowVelocity(r, false), r.target, r.R, r.inv_w, r.lo, r.hi);
  const double dl = next - l;
  ApplyJointImpulse(r, dl);
  l = next;
  return internal::RowChange(dl, r.inv_w);
}

}  // namespace mrh::render
