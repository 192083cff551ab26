// SPDX-License-Identifier: Apache-2.0
// World::FindDivergence: a diverged simulation is a fault to report, never a state to go on from.
#include <mujoco/mujoco.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "mrh/world/world.h"
#include "world/world_impl.h"

namespace mrh::world {
namespace {

constexpr char kLikelyCauses[] =
    "likely causes: rendering gains too stiff for the time step (stiffness, rot_stiffness, "
    "rotation_weight), a physics_dt too long for the scene, or a scene whose bodies are too "
    "light for its contacts";

std::string BodyName(const mjModel& m, int body) {
  return "body " + internal::Describe(m, mjOBJ_BODY, body);
}

// `value` with `digits` significant digits ("2.88", not "2.880000000000002").
std::string Rounded(double value, int digits) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.*g", digits, value);
  return text.data();
}

std::string At(const mjData& d) {
  return " at t = " + Rounded(d.time, 6) + " s";
}

// Joint j's positions and velocities are finite.
bool JointFinite(const mjModel& m, const mjData& d, int j) {
  const int qadr = m.jnt_qposadr[j];
  const int vadr = m.jnt_dofadr[j];
  const int nq = m.jnt_type[j] == mjJNT_FREE ? 7 : m.jnt_type[j] == mjJNT_BALL ? 4 : 1;
  const int nv = m.jnt_type[j] == mjJNT_FREE ? 6 : m.jnt_type[j] == mjJNT_BALL ? 3 : 1;
  bool finite = true;
  for (int k = 0; k < nq; ++k) finite = finite && std::isfinite(d.qpos[qadr + k]);
  for (int k = 0; k < nv; ++k) finite = finite && std::isfinite(d.qvel[vadr + k]);
  return finite;
}

// The COM speed (m/s) of the body of free joint j.
double FreeBodySpeed(const mjModel& m, const mjData& d, int j) {
  const int body = m.jnt_bodyid[j];
  // A free joint's qvel is the body origin's world velocity and the angular velocity in body
  // axes: v_Cm = v + R (ω_B × p_BCm).
  const mjtNum* v = d.qvel + m.jnt_dofadr[j];
  mjtNum lever_B[3], v_Cm[3], quat[4];
  mju_cross(lever_B, v + 3, m.body_ipos + 3 * body);
  mju_copy4(quat, d.qpos + m.jnt_qposadr[j] + 3);
  mju_normalize4(quat);
  mju_rotVecQuat(v_Cm, lever_B, quat);
  mju_addTo3(v_Cm, v);
  return mju_norm3(v_Cm);
}

}  // namespace

std::string World::FindDivergence(double max_body_speed) {
  const mjModel& m = *impl_->model;
  const mjData& d = *impl_->data;
  static constexpr std::array<int, 3> kBad = {mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC};
  static constexpr std::array<const char*, 3> kWhat = {"qpos", "qvel", "qacc"};
  for (std::size_t i = 0; i < kBad.size(); ++i) {
    const mjWarningStat& w = d.warning[kBad[i]];
    if (w.number == impl_->bad_number_seen[i]) continue;
    impl_->bad_number_seen[i] = w.number;
    const int dof = w.lastinfo;
    const int body = dof >= 0 && dof < m.nv ? m.dof_bodyid[dof] : -1;
    // MuJoCo's reset set the time back to 0: name the step in which it happened.
    return impl_->origin + ": the simulation diverged at t = " +
           Rounded(impl_->step_start_time + m.opt.timestep, 6) +
           " s: MuJoCo found a bad number in " + kWhat[i] +
           (body >= 0 ? " of " + BodyName(m, body) : std::string()) + " and reset the state; " +
           kLikelyCauses;
  }
  for (int j = 0; j < m.njnt; ++j) {
    const int body = m.jnt_bodyid[j];
    if (!JointFinite(m, d, j)) {
      return impl_->origin + ": the simulation diverged" + At(d) + ": " + BodyName(m, body) +
             " has a non-finite position or velocity; " + kLikelyCauses;
    }
    if (max_body_speed <= 0.0 || m.jnt_type[j] != mjJNT_FREE) continue;
    const double speed = FreeBodySpeed(m, d, j);
    if (speed > max_body_speed) {
      return impl_->origin + ": the simulation diverged" + At(d) + ": " + BodyName(m, body) +
             " moves at " + Rounded(speed, 4) +
             " m/s, over safety.max_body_speed = " + Rounded(max_body_speed, 4) + " m/s; " +
             kLikelyCauses;
    }
  }
  return {};
}

}  // namespace mrh::world
