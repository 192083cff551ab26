// SPDX-License-Identifier: Apache-2.0
// Joint coordinates from a body's state relative to its parent's (the synchronization of a
// locally simulated mechanism), and joint lookups.
#include <mujoco/mujoco.h>

#include <cmath>
#include <numbers>

#include "mrh/core/error.h"
#include "mrh/world/world.h"
#include "world/world_impl.h"

namespace mrh::world {
namespace {

using internal::NearestTurn;
using internal::ToQuat;
using internal::ToVec3;

// The state the joint coordinates are computed from: the child's and the parent's copies of
// the joint frame J (origin jnt_pos on the child; the body offset on the parent) and the
// relative velocity of the child over the parent at J's origin.
struct Relative {
  Vec3 pC, pP;  // J's origin on the child and on the parent (world)
  Quat qC, qP;  // J's orientation on the child and on the parent (world)
  Vec3 v, w;    // child over parent at pC: linear, angular (world)
};

Relative MakeRelative(const mjModel& m, int body, const Pose& X_WB, const Twist& V_WCm,
                      const Pose& X_WP, const Twist& V_WPcm) {
  const int parent = m.body_parentid[body];
  const Vec3 anchor =
      m.body_jntnum[body] > 0 ? ToVec3(m.jnt_pos + 3 * m.body_jntadr[body]) : Vec3::Zero();
  const Pose X_PJ = Pose{ToVec3(m.body_pos + 3 * body), ToQuat(m.body_quat + 4 * body)} *
                    Pose{anchor, Quat::Identity()};
  Relative r;
  r.qC = X_WB.q.normalized();
  r.pC = X_WB.p + r.qC * anchor;
  const Pose X_WJ = X_WP * X_PJ;
  r.pP = X_WJ.p;
  r.qP = X_WJ.q.normalized();
  const Vec3 c_child = X_WB * ToVec3(m.body_ipos + 3 * body);
  const Vec3 c_parent = X_WP * ToVec3(m.body_ipos + 3 * parent);
  r.w = V_WCm.w - V_WPcm.w;
  r.v = (V_WCm.v + V_WCm.w.cross(r.pC - c_child)) - (V_WPcm.v + V_WPcm.w.cross(r.pC - c_parent));
  return r;
}

// Joint `joint`'s coordinates from the relative state. Several slides of one body each take the
// displacement along their own axis (the anchors cancel: the body does not turn).
bool SetRelative(const mjModel& m, mjData* d, int joint, const Relative& r) {
  const int qadr = m.jnt_qposadr[joint];
  const int vadr = m.jnt_dofadr[joint];
  Quat rel = (r.qP.conjugate() * r.qC).normalized();
  const Vec3 axis_J = ToVec3(m.jnt_axis + 3 * joint).normalized();
  const Vec3 axis_W = r.qP * axis_J;
  switch (m.jnt_type[joint]) {
    case mjJNT_HINGE: {
      if (rel.w() < 0.0) rel.coeffs() *= -1.0;
      const double angle = NearestTurn(2.0 * std::atan2(rel.vec().dot(axis_J), rel.w()),
                                       d->qpos[qadr] - m.qpos0[qadr]);
      d->qpos[qadr] = m.qpos0[qadr] + angle;
      d->qvel[vadr] = axis_W.dot(r.w);
      return true;
    }
    case mjJNT_SLIDE:
      d->qpos[qadr] = m.qpos0[qadr] + axis_W.dot(r.pC - r.pP);
      d->qvel[vadr] = axis_W.dot(r.v);
      return true;
    case mjJNT_BALL: {
      const Vec3 w_C = r.qC.conjugate() * r.w;  // a ball's velocity is in the child's axes
      d->qpos[qadr] = rel.w();
      d->qpos[qadr + 1] = rel.x();
      d->qpos[qadr + 2] = rel.y();
      d->qpos[qadr + 3] = rel.z();
      for (int i = 0; i < 3; ++i) d->qvel[vadr + i] = w_C[i];
      return true;
    }
    default:
      return false;
  }
}

}  // namespace

bool World::SetBodyStateInParent(int body, const Pose& X_WB, const Twist& V_WCm,
                                 const Pose& X_WParent, const Twist& V_WParentCm) {
  const mjModel& m = *impl_->model;
  if (body <= 0 || body >= m.nbody) return false;
  if (!IsFinite(X_WB) || !IsFinite(V_WCm) || !IsFinite(X_WParent) || !IsFinite(V_WParentCm)) {
    return false;
  }
  const int count = m.body_jntnum[body];
  if (count == 0) return true;  // welded: follows its parent
  const int first = m.body_jntadr[body];
  for (int j = first; j < first + count; ++j) {
    if (count > 1 && m.jnt_type[j] != mjJNT_SLIDE) return false;
  }
  const Relative r = MakeRelative(m, body, X_WB, V_WCm, X_WParent, V_WParentCm);
  for (int j = first; j < first + count; ++j) {
    if (!SetRelative(m, impl_->data.get(), j, r)) return false;
  }
  impl_->kinematics_stale = true;
  return true;
}

int World::num_joints() const {
  return static_cast<int>(impl_->model->njnt);
}

int World::FindJoint(const std::string& name) const {
  return mj_name2id(impl_->model.get(), mjOBJ_JOINT, name.c_str());
}

double World::joint_position(int joint) const {
  const mjModel& m = *impl_->model;
  if (joint < 0 || joint >= m.njnt) throw InvalidArgument("joint id out of range");
  return impl_->data->qpos[m.jnt_qposadr[joint]];
}

}  // namespace mrh::world
