// SPDX-License-Identifier: Apache-2.0
// The global rigid-body world: a MuJoCo model and its state behind an engine-neutral interface.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/geometry/shape.h"

namespace mrh::world {

/// How a scene is loaded.
struct LoadOptions {
  /// Name of the mocap body that is the haptic pointer. Its geoms are made non-colliding inside
  /// MuJoCo (the haptic rendering handles the pointer's contacts). Empty: no pointer.
  std::string pointer_body = "pointer";
  /// Further pointer bodies (several pointers): each must be a mocap body, and its
  /// geoms are made non-colliding inside MuJoCo as pointer_body's are, so pointers never touch
  /// each other. Empty: one pointer.
  std::vector<std::string> more_pointer_bodies = {};
  /// Virtual coupling (B3): the pointer becomes a dynamic tool. Its mocap="true" is dropped from
  /// the scene text and a <freejoint/> added, and its geoms keep colliding inside MuJoCo. The
  /// rewritten text is loaded as by LoadString (relative asset paths resolve against the working
  /// directory). @throws mrh::SceneError naming the body if it cannot be rewritten.
  bool dynamic_pointer = false;
  /// With dynamic_pointer: the tool's mass (kg) instead of the geoms' (0: keep the geoms').
  double tool_mass = 0.0;
  /// With dynamic_pointer: the tool's principal inertia (kg·m², body-axes diagonal) instead of
  /// the geoms' (all zero: keep the geoms', scaled by tool_mass / geom mass if tool_mass > 0).
  Vec3 tool_inertia = Vec3::Zero();
  /// Contact-volume penalty (B2): MuJoCo's own contacts are switched off for the whole scene
  /// (mjDSBL_CONTACT); the method applies its penalty wrenches with AddForceAtPoint instead.
  bool penalty_contacts = false;
};

/// A geom of a body, as a convex shape fixed in the body frame.
struct GeomInfo {
  int id = -1;
  int body = -1;
  std::string name;       ///< may be empty
  geometry::Shape shape;  ///< convex shape in the geom frame G
  Pose X_BG;              ///< geom frame in its body frame
  bool collides = true;   ///< MuJoCo contype/conaffinity allow contacts
  /// Name of the MJCF material the geom uses (its `material` attribute); empty if none. It
  /// selects the geom's haptic material (session key `materials`).
  std::string material;
};

/// Static properties of a body. Body 0 is the world (static).
struct BodyInfo {
  int id = -1;
  std::string name;               ///< may be empty
  double mass = 0.0;              ///< kg
  Mat3 inertia_B = Mat3::Zero();  ///< rotational inertia about the COM, body-frame axes (kg·m²)
  Vec3 p_BCm = Vec3::Zero();      ///< centre of mass in the body frame (m)
  bool is_static = true;          ///< world body or welded to it (no degrees of freedom)
  bool is_mocap = false;
  int parent = -1;    ///< parent body id (0: the world body; -1 for the world body itself)
  bool free = false;  ///< moves on one free joint (its state is its own, not its parent's)
  /// MuJoCo's body_invweight0 (translational, 1/kg): the body's mobility under a force at
  /// qpos0, which sets its soft contacts' regularisation (1 / mass for a free body).
  double inv_weight = 0.0;
  std::vector<int> geoms;  ///< ids into World::geom()
};

/// Kinematic state of a body, world frame.
struct BodyState {
  Pose X_WB;                  ///< body frame pose
  Vec3 p_WCm = Vec3::Zero();  ///< centre of mass (m)
  Twist V_WCm;                ///< COM linear velocity and angular velocity (world frame)
};

/// Preallocated copy of the minimal simulation state (time, qpos, qvel, act, warm start, ctrl,
/// applied forces, mocap). Make one with World::MakeSnapshot() at setup; Save/Restore copy into
/// it without allocating.
class Snapshot {
 public:
  Snapshot();
  ~Snapshot();
  Snapshot(Snapshot&&) noexcept;
  Snapshot& operator=(Snapshot&&) noexcept;

 private:
  friend class World;
  std::vector<double> data_;
};

/// One MuJoCo model + data. Single-threaded: all calls from the physics thread (or the lockstep
/// loop). Nothing here is RT-safe.
class World {
 public:
  /// Loads an MJCF file. @throws mrh::SceneError naming the file and line on a bad scene, or
  /// when options.pointer_body is set but is not a mocap body of the scene.
  static World LoadFile(const std::filesystem::path& path, const LoadOptions& options = {});
  /// Loads MJCF text (`origin` names it in error messages). Same errors as LoadFile.
  static World LoadString(const std::string& xml, const LoadOptions& options = {},
                          const std::string& origin = "<string>");

  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  ~World();

  int num_bodies() const;
  /// The scene's name in error messages (its path, or the origin given to LoadString).
  const std::string& origin() const;
  /// Warnings found when the scene was loaded that mean the physics differs from the MJCF's
  /// text (a concave mesh replaced by its convex hull), one line each, naming the scene.
  const std::vector<std::string>& LoadWarnings() const;
  int num_geoms() const;
  const BodyInfo& body(int id) const;
  const GeomInfo& geom(int id) const;
  /// Body id by name, or -1.
  int FindBody(const std::string& name) const;
  /// The pointer body id, or -1 when the scene has none.
  int pointer_body() const;

  double timestep() const;
  /// @throws mrh::InvalidArgument if dt is not finite and > 0.
  void set_timestep(double dt);
  Vec3 gravity() const;
  void set_gravity(const Vec3& g);
  double time() const;

  /// Resets the state to the named MJCF keyframe (positions, velocities, mocap, time).
  /// @throws mrh::SceneError if there is no keyframe of that name (lists the ones there are).
  void ApplyKeyframe(const std::string& name);

  /// Advances one step of timestep() with the wrenches added since the last step, then clears
  /// them.
  void Step();

  /// Adds force f_W (N, world) acting at point p_W (m, world) on body `body` for the next step.
  void AddForceAtPoint(int body, const Vec3& f_W, const Vec3& p_W);
  /// Adds a wrench (world frame, torque about the body's COM) for the next step.
  void AddWrenchAtCom(int body, const Wrench& w_W);

  /// Sets the pose of a mocap body (the pointer). @pre body is a mocap body.
  void SetMocapPose(int body, const Pose& X_WB);
  /// Overwrites a free or slide/hinge-jointed body's pose and twist where its joints allow
  /// (used by synchronization with a local simulation). Returns false if the body's joints
  /// cannot represent it exactly.
  bool SetBodyState(int body, const Pose& X_WB, const Twist& V_WCm);

  /// Sets the one hinge, slide or ball joint of `body` (or its several slides; nothing for a
  /// body without joints) to
  /// the coordinates of the body's pose and twist relative to its parent, the parent given at
  /// pose X_WParent with COM twist V_WParentCm (e.g. from the same local simulation): the
  /// hinge angle of the relative rotation about the axis, the slide displacement along it, the
  /// ball's relative orientation, and the relative velocity along the coordinates. Components
  /// the joint cannot represent (a local simulation's joint drift) are dropped. Returns false
  /// for other joint configurations or non-finite input, leaving the state untouched.
  bool SetBodyStateInParent(int body, const Pose& X_WB, const Twist& V_WCm, const Pose& X_WParent,
                            const Twist& V_WParentCm);

  /// Number of joints, a joint's id by name (-1: none) and its position coordinate (hinge rad,
  /// slide m; the first coordinate of a ball or free joint).
  int num_joints() const;
  int FindJoint(const std::string& name) const;
  double joint_position(int joint) const;

  BodyState body_state(int body) const;
  /// World pose of a geom.
  Pose geom_pose(int geom) const;

  /// True when the world was loaded with LoadOptions::penalty_contacts (MuJoCo computes no
  /// contacts).
  bool penalty_contacts() const;
  /// Contacts in the last step (MuJoCo ncon) and constraint solver iterations used.
  int num_contacts() const;
  int solver_iterations() const;
  /// MuJoCo's warnings since loading (contact or constraint buffer full, bad qpos/qvel/qacc,
  /// singular inertia), one line each with its count and what to change in the scene. Empty when
  /// there were none. MuJoCo itself prints nothing and writes no MUJOCO_LOG.TXT: these lines are
  /// the only report (the engine copies them into RunStats::warnings).
  std::vector<std::string> SimulatorWarnings() const;
  /// After a step: why the simulation has diverged, or "" if it has not. Diverged means MuJoCo
  /// found a bad number in qpos, qvel or qacc since the last call (and reset the state), a joint
  /// coordinate or velocity is not finite, or a free body's centre of mass moves faster than
  /// `max_body_speed` (m/s; <= 0 disables the speed test). The text names the body, the time
  /// and the likely causes, in one line. Does not allocate unless it reports.
  std::string FindDivergence(double max_body_speed);

  Snapshot MakeSnapshot() const;
  void Save(Snapshot* snapshot) const;
  void Restore(const Snapshot& snapshot);

  /// qpos and qvel, for hashing and tests.
  std::span<const double> qpos() const;
  std::span<const double> qvel() const;

 private:
  friend class Perturber;  // perturbation runs work on the MuJoCo data directly (perturbation.h)
  friend class ContactExporter;    // local contact model export (contact_export.h)
  friend class AcceleranceAccess;  // analytic accelerance and converged reference (accelerance.h)
  struct Impl;
  explicit World(std::unique_ptr<Impl> impl);
  /// LoadString with relative asset paths resolved against `directory` (empty: the working
  /// directory): LoadFile's rewritten dynamic-pointer text keeps its scene's folder.
  static World LoadText(const std::string& xml, const LoadOptions& options,
                        const std::string& origin, const std::filesystem::path& directory);
  std::unique_ptr<Impl> impl_;
};

}  // namespace mrh::world
