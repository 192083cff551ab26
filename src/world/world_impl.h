// SPDX-License-Identifier: Apache-2.0
// Private state of World: the MuJoCo model and data, and the engine-neutral model description.
#pragma once

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "mrh/world/world.h"

namespace mrh::world {
namespace internal {

/// A MuJoCo 3-vector (mjtNum[3]) as a Vec3.
inline Vec3 ToVec3(const mjtNum* v) {
  return Vec3(v[0], v[1], v[2]);
}

/// A MuJoCo quaternion (mjtNum[4], w x y z) as a unit Quat.
inline Quat ToQuat(const mjtNum* q) {
  return Quat(q[0], q[1], q[2], q[3]).normalized();
}

/// Hinge angles are not wrapped: `angle` (rad) moved by whole turns to the one nearest
/// `current`.
inline double NearestTurn(double angle, double current) {
  return angle + 2.0 * std::numbers::pi * std::round((current - angle) / (2.0 * std::numbers::pi));
}

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};

struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

/// True if neither `body` nor any of its ancestors has a joint: the world, bodies welded to it
/// and mocap bodies (whose poses the user sets) with what is welded to them. (MuJoCo 3's
/// body_weldid does not map mocap bodies to the world.)
inline bool HasNoDofs(const mjModel& m, int body) {
  for (int b = body; b > 0; b = m.body_parentid[b]) {
    if (m.body_jntnum[b] > 0) return false;
  }
  return true;
}

/// Recomputes MuJoCo's per-body collision masks (body_contype, body_conaffinity: the OR over the
/// body's geoms, which the broadphase tests before any geom) after geom masks changed.
inline void RefreshBodyCollisionMasks(mjModel* m, int body) {
  int contype = 0;
  int conaffinity = 0;
  for (int g = m->body_geomadr[body]; g >= 0 && g < m->body_geomadr[body] + m->body_geomnum[body];
       ++g) {
    contype |= m->geom_contype[g];
    conaffinity |= m->geom_conaffinity[g];
  }
  m->body_contype[body] = contype;
  m->body_conaffinity[body] = conaffinity;
}

/// An object of `m` for messages: "'name'", or "#id" when it has no name.
std::string Describe(const mjModel& m, mjtObj type, int id);

/// Bodies and geoms of `m` as engine-neutral descriptions. `origin` names the scene in errors.
/// @throws mrh::SceneError for a geom type mrhaptics cannot represent (height field).
void DescribeModel(const mjModel& m, const std::string& origin, std::vector<BodyInfo>* bodies,
                   std::vector<GeomInfo>* geoms);

/// Number of doubles in a snapshot of `m`'s simulation state.
std::size_t SnapshotSize(const mjModel& m);

/// Sets the joint coordinates of `body` to reproduce pose X_WB and COM twist V_WCm, if its
/// joints can (see World::SetBodyState). Kinematics in `d` must be current (a free joint's
/// coordinates do not read them). Leaves `d`
/// untouched and returns false otherwise.
bool SetJointsFromBodyState(const mjModel& m, mjData* d, int body, const Pose& X_WB,
                            const Twist& V_WCm);

/// Everything a World owns. (World::Impl derives from it so that free functions in the
/// implementation can work on it.)
struct WorldState {
  internal::ModelPtr model;
  internal::DataPtr data;
  std::string origin;                      // the scene's name in error messages
  std::vector<std::string> load_warnings;  // World::LoadWarnings()
  std::vector<BodyInfo> bodies;
  std::vector<GeomInfo> geoms;
  int pointer_body = -1;
  std::size_t snapshot_size = 0;
  // Set when qpos, qvel or mocap changed without MuJoCo recomputing positions (after mj_step the
  // positions it holds are those at the start of the step). Getters refresh on demand.
  bool kinematics_stale = false;
  // MuJoCo's bad qpos/qvel/qacc warning counts at the last FindDivergence call, and the time at
  // the start of the last World::Step (a reset inside the step sets d->time back to 0).
  std::array<int, 3> bad_number_seen{};
  double step_start_time = 0.0;

  /// Recomputes body and geom poses and body velocities from qpos, qvel and mocap if stale.
  /// Does not allocate.
  void EnsureKinematics() {
    if (!kinematics_stale) return;
    mj_kinematics(model.get(), data.get());
    mj_comPos(model.get(), data.get());
    mj_comVel(model.get(), data.get());
    kinematics_stale = false;
  }
};

/// Solver iterations of the last step: the most any constraint island took (MuJoCo 3 counts them
/// per island, the first mjNISLAND islands; one count when islands are off or there are none).
inline int SolverIterations(const mjData& d) {
  const int islands = std::clamp(d.nisland, 1, static_cast<int>(mjNISLAND));
  return *std::max_element(d.solver_niter, d.solver_niter + islands);
}

/// Which of MuJoCo's memory sizes the scene's MJCF text sets itself (<size memory njmax
/// nconmax>; comments skipped, <include>d files not read).
struct ExplicitSizes {
  bool memory = false, njmax = false, nconmax = false;

  bool any() const { return memory || njmax || nconmax; }
};

ExplicitSizes FindExplicitSizes(const std::string& mjcf);

/// The bytes of mjData's arena (contacts, constraints and the solver's stack) for `m`
/// (model_size.cc): generous for every moving geom resting among neighbours, and never more
/// than MuJoCo's own default (m.narena as compiled), which grows with the square of the dofs.
/// The arena is allocated untouched: only the part a step uses costs memory.
std::int64_t PlanArena(const mjModel& m);

/// Sets m.narena from PlanArena unless the scene sizes MuJoCo's memory itself.
void SizeArena(mjModel* m, const ExplicitSizes& explicit_sizes);

/// While alive, MuJoCo errors raised on this thread name `scene` (see load.cc). RT-safe (one
/// thread_local pointer store). `scene` must outlive the scope.
class MujocoScope {
 public:
  explicit MujocoScope(const std::string& scene);
  ~MujocoScope();
  MujocoScope(const MujocoScope&) = delete;
  MujocoScope& operator=(const MujocoScope&) = delete;

 private:
  const std::string* previous_;
};

/// Loads `model` into `state`: describes bodies and geoms, sets up the pointer, makes the data
/// and computes everything derived from the initial state.
/// @throws mrh::SceneError naming `origin` for a scene mrhaptics cannot use.
void InitializeState(ModelPtr model, const std::string& origin, const LoadOptions& options,
                     WorldState* state);

/// LoadOptions::dynamic_pointer: the scene text with the pointer body's mocap="true" removed
/// and a <freejoint/> added. @throws mrh::SceneError naming the body.
std::string MakePointerDynamic(const std::string& xml, const std::string& name,
                               const std::string& origin);

/// The rewritten pointer as a tool: checks its free joint, applies tool_mass / tool_inertia and
/// updates `info`. The caller runs mj_setConst once the data exists. @throws mrh::SceneError.
void SetUpDynamicPointer(mjModel* m, int body, const LoadOptions& options,
                         const std::string& origin, BodyInfo* info);

}  // namespace internal

struct World::Impl : internal::WorldState {};

}  // namespace mrh::world
