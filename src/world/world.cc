// SPDX-License-Identifier: Apache-2.0
// World over MuJoCo 2.2: stepping, applied wrenches, mocap, keyframes and state queries.
#include "mrh/world/world.h"

#include <mujoco/mujoco.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "mrh/core/assert.h"
#include "mrh/core/error.h"
#include "world/world_impl.h"

namespace mrh::world {
namespace {

using internal::ToVec3;

void CheckBody(const mjModel& m, int body) {
  MRH_DEMAND(body >= 0 && body < m.nbody);
}

}  // namespace

int World::num_bodies() const {
  return static_cast<int>(impl_->model->nbody);
}

int World::num_geoms() const {
  return static_cast<int>(impl_->model->ngeom);
}

const BodyInfo& World::body(int id) const {
  CheckBody(*impl_->model, id);
  return impl_->bodies[static_cast<std::size_t>(id)];
}

const GeomInfo& World::geom(int id) const {
  MRH_DEMAND(id >= 0 && id < impl_->model->ngeom);
  return impl_->geoms[static_cast<std::size_t>(id)];
}

int World::FindBody(const std::string& name) const {
  return mj_name2id(impl_->model.get(), mjOBJ_BODY, name.c_str());
}

int World::pointer_body() const {
  return impl_->pointer_body;
}

double World::timestep() const {
  return impl_->model->opt.timestep;
}

void World::set_timestep(double dt) {
  if (!std::isfinite(dt) || dt <= 0.0) {
    throw InvalidArgument("World::set_timestep: dt = " + std::to_string(dt) +
                          " s; expected a finite value > 0 (e.g. 0.02)");
  }
  impl_->model->opt.timestep = dt;
}

Vec3 World::gravity() const {
  return ToVec3(impl_->model->opt.gravity);
}

void World::set_gravity(const Vec3& g) {
  for (int i = 0; i < 3; ++i) impl_->model->opt.gravity[i] = g[i];
}

double World::time() const {
  return impl_->data->time;
}

void World::ApplyKeyframe(const std::string& name) {
  const mjModel* m = impl_->model.get();
  const int key = mj_name2id(m, mjOBJ_KEY, name.c_str());
  if (key < 0) {
    std::string known;
    for (int k = 0; k < m->nkey; ++k) {
      const char* key_name = mj_id2name(m, mjOBJ_KEY, k);
      known += (known.empty() ? "'" : ", '") + std::string(key_name ? key_name : "") + "'";
    }
    throw SceneError(impl_->origin + ": no keyframe named '" + name + "'; " +
                     (known.empty() ? "the scene has no keyframes: add <keyframe><key name=\"" +
                                          name + "\" .../></keyframe>"
                                    : "the scene has " + known));
  }
  mj_resetDataKeyframe(m, impl_->data.get(), key);
  mj_forward(m, impl_->data.get());
  impl_->kinematics_stale = false;
}

void World::Step() {
  const internal::MujocoScope scope(impl_->origin);
  mjData* d = impl_->data.get();
  impl_->step_start_time = d->time;
  mj_step(impl_->model.get(), d);
  // The wrenches were for this step only.
  mju_zero(d->xfrc_applied, static_cast<int>(6 * impl_->model->nbody));
  impl_->kinematics_stale = true;
}

// MuJoCo's xfrc_applied holds, per body, a world-frame force and a torque about the body's
// centre of mass (xipos), both applied for the next step.
void World::AddForceAtPoint(int body, const Vec3& f_W, const Vec3& p_W) {
  CheckBody(*impl_->model, body);
  impl_->EnsureKinematics();
  const Vec3 p_CmP_W = p_W - ToVec3(impl_->data->xipos + 3 * body);
  AddWrenchAtCom(body, Wrench{f_W, p_CmP_W.cross(f_W)});
}

void World::AddWrenchAtCom(int body, const Wrench& w_W) {
  CheckBody(*impl_->model, body);
  mjtNum* xfrc = impl_->data->xfrc_applied + 6 * body;
  for (int i = 0; i < 3; ++i) {
    xfrc[i] += w_W.f[i];
    xfrc[3 + i] += w_W.tau[i];
  }
}

void World::SetMocapPose(int body, const Pose& X_WB) {
  CheckBody(*impl_->model, body);
  const int mocap = impl_->model->body_mocapid[body];
  MRH_DEMAND(mocap >= 0);
  mjData* d = impl_->data.get();
  const Quat q = X_WB.q.normalized();
  for (int i = 0; i < 3; ++i) d->mocap_pos[3 * mocap + i] = X_WB.p[i];
  d->mocap_quat[4 * mocap + 0] = q.w();
  d->mocap_quat[4 * mocap + 1] = q.x();
  d->mocap_quat[4 * mocap + 2] = q.y();
  d->mocap_quat[4 * mocap + 3] = q.z();
  impl_->kinematics_stale = true;
}

bool World::SetBodyState(int body, const Pose& X_WB, const Twist& V_WCm) {
  CheckBody(*impl_->model, body);
  // A free joint's coordinates follow from the model alone; slide and hinge joints need their
  // parent's pose. Skipping the refresh for free bodies saves a whole-world kinematics pass per
  // body written (the contact local model writes every owned island body each step).
  const mjModel& m = *impl_->model;
  if (m.body_jntnum[body] != 1 || m.jnt_type[m.body_jntadr[body]] != mjJNT_FREE) {
    impl_->EnsureKinematics();
  }
  if (!internal::SetJointsFromBodyState(*impl_->model, impl_->data.get(), body, X_WB, V_WCm)) {
    return false;
  }
  impl_->kinematics_stale = true;
  return true;
}

BodyState World::body_state(int body) const {
  CheckBody(*impl_->model, body);
  impl_->EnsureKinematics();
  const mjData* d = impl_->data.get();
  BodyState state;
  state.X_WB =
      Pose{ToVec3(d->xpos + 3 * body), Quat(d->xquat[4 * body], d->xquat[4 * body + 1],
                                            d->xquat[4 * body + 2], d->xquat[4 * body + 3])};
  state.p_WCm = ToVec3(d->xipos + 3 * body);
  // [angular; linear] at the COM (xipos), world axes (flg_local = 0).
  std::array<mjtNum, 6> velocity{};
  mj_objectVelocity(impl_->model.get(), d, mjOBJ_BODY, body, velocity.data(), 0);
  state.V_WCm = Twist{ToVec3(velocity.data() + 3), ToVec3(velocity.data())};
  return state;
}

Pose World::geom_pose(int geom) const {
  MRH_DEMAND(geom >= 0 && geom < impl_->model->ngeom);
  impl_->EnsureKinematics();
  const mjData* d = impl_->data.get();
  std::array<mjtNum, 4> q{};
  mju_mat2Quat(q.data(), d->geom_xmat + 9 * geom);
  return Pose{ToVec3(d->geom_xpos + 3 * geom), Quat(q[0], q[1], q[2], q[3])};
}

bool World::penalty_contacts() const {
  return (impl_->model->opt.disableflags & mjDSBL_CONTACT) != 0;
}

int World::num_contacts() const {
  return impl_->data->ncon;
}

int World::solver_iterations() const {
  return internal::SolverIterations(*impl_->data);
}

std::vector<std::string> World::SimulatorWarnings() const {
  struct Kind {
    int index;
    const char* what;
    const char* fix;
  };

  static constexpr std::array<Kind, 7> kKinds{{
      {mjWARN_INERTIA, "(near) singular inertia matrix", "give every body positive mass/inertia"},
      {mjWARN_CONTACTFULL, "contact buffer full, contacts dropped",
       "raise <size nconmax=...> or <size memory=...> in the scene, or remove them"},
      {mjWARN_CNSTRFULL, "constraint buffer full, constraints dropped",
       "raise <size memory=...> (or njmax) in the scene, or remove it"},
      {mjWARN_BADQPOS, "bad number in qpos, state reset", "lower the timestep or the gains"},
      {mjWARN_BADQVEL, "bad number in qvel, state reset", "lower the timestep or the gains"},
      {mjWARN_BADQACC, "bad number in qacc, state reset", "lower the timestep or the gains"},
      {mjWARN_BADCTRL, "bad number in ctrl, ignored", "check the scene's actuators"},
  }};
  std::vector<std::string> lines;
  const mjData* d = impl_->data.get();
  for (const Kind& kind : kKinds) {
    const int count = d->warning[kind.index].number;
    if (count <= 0) continue;
    lines.push_back(impl_->origin + ": MuJoCo warned " + std::to_string(count) +
                    " time(s): " + kind.what + " (last info " +
                    std::to_string(d->warning[kind.index].lastinfo) + "); " + kind.fix);
  }
  return lines;
}

std::span<const double> World::qpos() const {
  return {impl_->data->qpos, static_cast<std::size_t>(impl_->model->nq)};
}

std::span<const double> World::qvel() const {
  return {impl_->data->qvel, static_cast<std::size_t>(impl_->model->nv)};
}

}  // namespace mrh::world
