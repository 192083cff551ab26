// SPDX-License-Identifier: Apache-2.0
// Joint kinematics for the Perturber (perturbation_kinematics.h).
#include "world/perturbation_kinematics.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>

#include "world/world_impl.h"

namespace mrh::world::internal {

bool IsFreeBody(const mjModel& m, int body) {
  return m.body_jntnum[body] == 1 && m.jnt_type[m.body_jntadr[body]] == mjJNT_FREE;
}

bool IsSlideBody(const mjModel& m, int body) {
  const int count = m.body_jntnum[body];
  if (count == 0 || !internal::HasNoDofs(m, m.body_parentid[body])) return false;
  for (int j = m.body_jntadr[body]; j < m.body_jntadr[body] + count; ++j) {
    if (m.jnt_type[j] != mjJNT_SLIDE) return false;
  }
  return true;
}

Twist TwistAfterEuler(const mjModel& m, const mjData& d, int body, double dt, const mjtNum* qacc) {
  const int joint = m.body_jntadr[body];
  if (IsFreeBody(m, body)) {
    const int qadr = m.jnt_qposadr[joint];
    const int vadr = m.jnt_dofadr[joint];
    std::array<mjtNum, 6> qvel{};
    for (int i = 0; i < 6; ++i) qvel[i] = d.qvel[vadr + i] + dt * qacc[vadr + i];
    std::array<mjtNum, 4> quat{};
    std::copy_n(d.qpos + qadr + 3, 4, quat.data());
    if (dt > 0.0) mju_quatIntegrate(quat.data(), qvel.data() + 3, dt);
    mju_normalize4(quat.data());  // as mj_kinematics does
    std::array<mjtNum, 9> R{};
    mju_quat2Mat(R.data(), quat.data());
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R_WB(R.data());
    // Free-joint qvel: body-origin velocity (world axes), then angular velocity (body axes).
    const Vec3 w_W = R_WB * Vec3(qvel[3], qvel[4], qvel[5]);
    const Vec3 p_BoCm_W = R_WB * ToVec3(m.body_ipos + 3 * body);
    return Twist{Vec3(qvel[0], qvel[1], qvel[2]) + w_W.cross(p_BoCm_W), w_W};
  }
  Twist twist;
  for (int j = joint; j < joint + m.body_jntnum[body]; ++j) {
    const int vadr = m.jnt_dofadr[j];
    twist.v += ToVec3(d.xaxis + 3 * j) * (d.qvel[vadr] + dt * qacc[vadr]);
  }
  return twist;
}

}  // namespace mrh::world::internal
