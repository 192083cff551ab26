// SPDX-License-Identifier: Apache-2.0
// Joint coordinates that put a body at a given pose and COM twist (free, slide or hinge joints).
#include <mujoco/mujoco.h>

#include <Eigen/QR>
#include <cmath>
#include <numbers>

#include "world/world_impl.h"

namespace mrh::world::internal {
namespace {

// A state "can be represented" when the joints reproduce it to within these. States come from
// another simulation of the same body, so a representable state agrees to roundoff.
constexpr double kPositionTolerance = 1e-9;  // m
constexpr double kAngleTolerance = 1e-9;     // rad
constexpr double kVelocityTolerance = 1e-9;  // m/s and rad/s
// Bodies with more slide joints than this are not handled (3 already span all translations).
constexpr int kMaxSlides = 6;

// World pose of the body frame with its own joints at their reference (qpos0) values: the
// parent's pose composed with the body's offset.
Pose PoseBeforeJoints(const mjModel& m, const mjData& d, int body) {
  const int parent = m.body_parentid[body];
  const Pose X_WP{ToVec3(d.xpos + 3 * parent), ToQuat(d.xquat + 4 * parent)};
  return X_WP * Pose{ToVec3(m.body_pos + 3 * body), ToQuat(m.body_quat + 4 * body)};
}

// A free joint's qpos is the body origin and orientation in the world; its qvel is the origin's
// linear velocity in world axes followed by the angular velocity in body axes (MuJoCo 2.2,
// checked by tests/world).
bool SetFree(const mjModel& m, mjData* d, int body, const Pose& X_WB, const Twist& V_WCm) {
  const int joint = m.body_jntadr[body];
  const Quat q = X_WB.q.normalized();
  const Vec3 p_WCm = X_WB.p + q * ToVec3(m.body_ipos + 3 * body);
  const Vec3 v_WBo = V_WCm.v + V_WCm.w.cross(X_WB.p - p_WCm);
  const Vec3 w_B = q.conjugate() * V_WCm.w;
  mjtNum* qpos = d->qpos + m.jnt_qposadr[joint];
  mjtNum* qvel = d->qvel + m.jnt_dofadr[joint];
  for (int i = 0; i < 3; ++i) {
    qpos[i] = X_WB.p[i];
    qvel[i] = v_WBo[i];
    qvel[3 + i] = w_B[i];
  }
  qpos[3] = q.w();
  qpos[4] = q.x();
  qpos[5] = q.y();
  qpos[6] = q.z();
  return true;
}

// Slide joints translate the body along their axes (fixed in the parent) by qpos - qpos0.
bool SetSlides(const mjModel& m, mjData* d, int body, const Pose& X_WB, const Twist& V_WCm) {
  const int first = m.body_jntadr[body];
  const int count = m.body_jntnum[body];
  const Pose X_W0 = PoseBeforeJoints(m, *d, body);
  if (count > kMaxSlides || X_W0.q.angularDistance(X_WB.q) > kAngleTolerance ||
      V_WCm.w.norm() > kVelocityTolerance) {
    return false;
  }
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxSlides> axes(3, count);
  for (int i = 0; i < count; ++i) axes.col(i) = X_W0.q * ToVec3(m.jnt_axis + 3 * (first + i));
  // Least squares (minimum norm if the axes are dependent); the residual says whether the
  // axes span the requested displacement and velocity.
  const Vec3 displacement = X_WB.p - X_W0.p;
  const auto solver = axes.completeOrthogonalDecomposition();
  const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxSlides, 1> s = solver.solve(displacement);
  const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxSlides, 1> s_dot = solver.solve(V_WCm.v);
  if ((axes * s - displacement).norm() > kPositionTolerance ||
      (axes * s_dot - V_WCm.v).norm() > kVelocityTolerance) {
    return false;
  }
  for (int i = 0; i < count; ++i) {
    const int qadr = m.jnt_qposadr[first + i];
    d->qpos[qadr] = m.qpos0[qadr] + s[i];
    d->qvel[m.jnt_dofadr[first + i]] = s_dot[i];
  }
  return true;
}

// A hinge rotates the body by qpos - qpos0 about its axis through its anchor (jnt_pos), both
// fixed in the body frame before the rotation.
bool SetHinge(const mjModel& m, mjData* d, int body, const Pose& X_WB, const Twist& V_WCm) {
  const int joint = m.body_jntadr[body];
  const Pose X_W0 = PoseBeforeJoints(m, *d, body);
  const Vec3 axis_B = ToVec3(m.jnt_axis + 3 * joint).normalized();
  const Vec3 anchor_B = ToVec3(m.jnt_pos + 3 * joint);
  const Vec3 anchor_W = X_W0 * anchor_B;
  const Vec3 axis_W = X_W0.q * axis_B;
  const Quat rotation = X_W0.q.conjugate() * X_WB.q.normalized();
  double angle = 2.0 * std::atan2(rotation.vec().dot(axis_B), rotation.w());
  const Quat q = X_W0.q * Quat(Eigen::AngleAxisd(angle, axis_B));
  const double angle_dot = V_WCm.w.dot(axis_W);
  const Vec3 p_WCm = X_WB.p + q * ToVec3(m.body_ipos + 3 * body);
  if (q.angularDistance(X_WB.q) > kAngleTolerance ||
      (anchor_W - q * anchor_B - X_WB.p).norm() > kPositionTolerance ||
      (V_WCm.w - angle_dot * axis_W).norm() > kVelocityTolerance ||
      (V_WCm.w.cross(p_WCm - anchor_W) - V_WCm.v).norm() > kVelocityTolerance) {
    return false;
  }
  const int qadr = m.jnt_qposadr[joint];
  angle = NearestTurn(angle, d->qpos[qadr] - m.qpos0[qadr]);
  d->qpos[qadr] = m.qpos0[qadr] + angle;
  d->qvel[m.jnt_dofadr[joint]] = angle_dot;
  return true;
}

}  // namespace

bool SetJointsFromBodyState(const mjModel& m, mjData* d, int body, const Pose& X_WB,
                            const Twist& V_WCm) {
  const int count = m.body_jntnum[body];
  if (count == 0 || !IsFinite(X_WB) || !IsFinite(V_WCm)) return false;
  const int first = m.body_jntadr[body];
  if (count == 1 && m.jnt_type[first] == mjJNT_FREE) return SetFree(m, d, body, X_WB, V_WCm);
  // Slide and hinge coordinates are relative to the parent, which must not move.
  if (!HasNoDofs(m, m.body_parentid[body])) return false;
  if (count == 1 && m.jnt_type[first] == mjJNT_HINGE) return SetHinge(m, d, body, X_WB, V_WCm);
  for (int j = first; j < first + count; ++j) {
    if (m.jnt_type[j] != mjJNT_SLIDE) return false;
  }
  return SetSlides(m, d, body, X_WB, V_WCm);
}

}  // namespace mrh::world::internal
