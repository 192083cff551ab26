// SPDX-License-Identifier: Apache-2.0
// Private state of World: the MuJoCo model and data, and the engine-neutral model description.
#pragma once

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "mrh/world/world.h"

namespace mrh::world {
namespace internal {

/// A MuJoCo 3-vector (mjtNum[3]) as a Vec3.
inline Vec3 ToVec3(const mjtNum* v) {
  return Vec3(v[0], v[1], v[2]);
}

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};

struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

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
  std::string origin;  // the scene's name in error messages
  std::vector<std::string> load_warnings;  // World::LoadWarnings()
  std::vector<BodyInfo> bodies;
  std::vector<GeomInfo> geoms;
  int pointer_body = -1;
  std::size_t snapshot_size = 0;
  // Set when qpos, qvel or mocap changed without MuJoCo recomputing positions (after mj_step the
  // positions it holds are those at the start of the step). Getters refresh on demand.
  bool kinematics_stale = false;
  // mjtNums of data->stack whose pages have been touched (TouchStack).
  std::int64_t stack_touched = 0;

  /// Recomputes body and geom poses and body velocities from qpos, qvel and mocap if stale.
  /// Does not allocate.
  void EnsureKinematics() {
    if (!kinematics_stale) return;
    mj_kinematics(model.get(), data.get());
    mj_comPos(model.get(), data.get());
    mj_comVel(model.get(), data.get());
    kinematics_stale = false;
  }

  /// Touches the pages of MuJoCo's stack (data->stack) up to `mjtnums` (at most nstack), when
  /// the stack is free (between MuJoCo calls). The stack is one block that mj_makeData leaves
  /// unmapped, and the kernel maps each page on its first touch (~3-10 µs here): left to the
  /// solver, a 500-box step with friction mapped them during steps, at 33 ms p99 against a 4-6 ms
  /// median (issue 13; Newton allocates 3 nv² mjtNums and reaches new parts of that as contacts
  /// change). Does not allocate.
  void TouchStack(std::int64_t mjtnums) {
    const std::int64_t end = std::min<std::int64_t>(model->nstack, mjtnums);
    if (end <= stack_touched) return;
    std::memset(data->stack + stack_touched, 0,
                sizeof(mjtNum) * static_cast<std::size_t>(end - stack_touched));
    stack_touched = end;
  }

  /// After a step: keeps the stack touched ~6 % beyond its deepest use so far (maxuse_stack), so a
  /// use that grows with the contacts maps its pages here, now and then, not inside a step.
  void TouchStackAfterStep() {
    const std::int64_t used = data->maxuse_stack;
    if (used + used / 64 > stack_touched) TouchStack(used + used / 16);
  }
};

/// Which of MuJoCo's buffer sizes the scene's MJCF text sets itself (<size njmax nconmax
/// nstack>; comments skipped, <include>d files not read).
struct ExplicitSizes {
  bool njmax = false, nconmax = false, nstack = false;
};
ExplicitSizes FindExplicitSizes(const std::string& mjcf);

/// MuJoCo 2.2.2 buffer sizes for `m` (model_size.cc): contacts and constraint rows its moving
/// geoms need resting among neighbours with the scene's largest condim and its cone, the
/// stack its solver needs, and the most rows MuJoCo 2.2.2 can allocate with m.nv dofs.
struct BufferPlan {
  std::int64_t nconmax = 0, njmax = 0, nstack = 0;
  std::int64_t resting_rows = 0;  ///< rows of the floor contacts alone
  std::int64_t max_rows = 0;      ///< njmax limit of MuJoCo 2.2.2's int-sized data buffer
  std::int64_t buffer_bytes = 0;  ///< constraint and contact arrays at njmax, nconmax
  std::int64_t stack_use = 0;     ///< the stack the solver is expected to use (half of nstack)
};
BufferPlan PlanBuffers(const mjModel& m);

/// Sets m's nconmax, njmax and nstack from PlanBuffers, except those the scene sets itself.
/// @throws mrh::SceneError naming `origin` if the rows its resting contacts need exceed what
/// MuJoCo 2.2.2 can allocate.
void SizeBuffers(mjModel* m, const ExplicitSizes& explicit_sizes, const std::string& origin);

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
