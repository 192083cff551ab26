// SPDX-License-Identifier: Apache-2.0
// proxy-6dof's reaction evaluated on the physics side at the objects' current poses.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "geometric_ir_builder.h"
#include "mrh/core/fixed_vector.h"
#include "mrh/core/spatial.h"
#include "mrh/ir/local_contact.h"
#include "mrh/ir/snapshot.h"
#include "mrh/render/ir_interpolator.h"
#include "mrh/render/local_contact_solver.h"
#include "mrh/render/proxy_renderer.h"
#include "mrh/render/tick_ir.h"
#include "mrh/world/contact_export.h"

namespace mrh::world {
class World;
}

namespace mrh::physics::internal {

/// rendering.proxy_reaction = "local": how the physics step applies proxy-6dof's reaction so
/// that light objects stay stable at physics_dt = 20 ms.
///
/// The plain method applies the period's impulse J/Δt^G, measured by the haptic side against the
/// object pose of two steps ago; for a light object that loop's gain k_r Δt²/I is well above 1
/// (about 10 for t3.6's box), and it flings the object. Instead, each physics step:
/// 1. builds its own geometric IR of the objects as they are now, for the pointer where it will
///    be at the step's end (the report's pose moved on with the report's velocity), so the
///    contact points cover the region it will penetrate;
/// 2. runs a second ProxyRenderer (the haptic one's settings) at the haptic rate h over the
///    step, the pointer moving on with the report's velocity, against that IR re-posed for each
///    touched object's predicted pose. The touched free bodies and every free body they touch
///    (their contact island, world::ContactExporter, as local-dynamics exports it) are simulated
///    at h by render::LocalContactSolver under gravity, their contacts (normal + Coulomb cone)
///    and the proxy's reaction. A touched body outside such an island (a hinged one, or beyond
///    the island's capacity) is integrated as a free rigid body under the reaction plus the rest
///    of the world's wrench on it, estimated from its last step (the velocity change the
///    applied reaction did not cause);
/// 3. AfterStep (after World::Step) sets every island body to the local run's end state, the
///    step's contact forces and friction having been resolved together with the reaction at h
///    (a friction force estimated one 20 ms step late would stick and slip in turn, moving the
///    body in jerks). A body outside an island gets the
///    constant wrench J/Δt^G whose impulse J gives the world's step the local run's
///    displacement (MuJoCo's semi-implicit step moves a body by its end-of-step velocity, so J
///    sets that velocity to the local run's mean one, less the rest of the world's share).
///    applied() reports the reaction the world received: those J, and for island bodies the
///    physics-side proxy's reaction integral, which the overwrite passes on together with the
///    contact forces the island met under it.
/// The haptic side (what the user feels) is the thesis' proxy, unchanged.
///
/// Momentum accounting: applied() is what the world received (PhysicsSide counts it in
/// RunStats::impulses). The physics-side proxy's own reaction integral (proxy_impulses()) obeys
/// action = reaction with pointer_impulse() about any common point; for island bodies applied()
/// is that integral; for a body outside an island it differs from it by the local run's
/// end-of-step oscillation (the step cannot represent it), so there momentum between pointer
/// and objects is conserved only on average, not per step.
///
/// Physics thread only; not RT-safe (it runs next to World::Step). No allocation after
/// construction.
class ProxyLocalReaction {
 public:
  /// @param haptic_dt the substep h (s, > 0); physics_dt/h substeps per step (at least 1).
  /// @throws mrh::InvalidArgument from the renderer settings.
  /// @throws mrh::SceneError from GeometricIrBuilder.
  ProxyLocalReaction(world::World& world, int pointer_body,
                     const settings::RenderingSettings& rendering,
                     const render::ProxyRendererSettings& settings, double physics_dt,
                     double haptic_dt);

  /// Several pointers: one more pointer with its own geometry and proxy settings, run over the
  /// same steps against the same objects and island (pointer index = the order of the calls,
  /// the constructor's being 0). Setup only. @throws as the constructor.
  void AddPointer(world::World& world, int pointer_body,
                  const settings::RenderingSettings& rendering,
                  const render::ProxyRendererSettings& settings);

  /// Computes the step's reaction for the pointer pose and velocity of `report` and adds it to
  /// `world` as constant wrenches for its next Step. Call before SetMocapPose / Step.
  void Apply(world::World& world, const ir::HapticReport& report);
  /// The same for every pointer at once (one report per pointer, in pointer order): each
  /// substep renders every pointer's proxy against the objects' current local poses, and the
  /// objects move once under all their reactions.
  void Apply(world::World& world, std::span<const ir::HapticReport* const> reports);
  /// Call after the World::Step that followed Apply: the island bodies take the local run's end
  /// state (nothing happens when the pointer touched no island body).
  void AfterStep(world::World& world);

  /// What the last Apply gave the world: per body, linear (N·s) and angular (N·m·s about the
  /// body's COM at the step's start) impulse; last_force is the last substep's force (N).
  const ir::HapticReport& applied() const noexcept { return applied_; }

  /// The physics-side proxy's reaction on each body integrated over the last Apply (angular
  /// about the body's COM at the step's start).
  const ir::HapticReport& proxy_impulses() const noexcept { return proxy_; }

  /// The physics-side proxy's wrench on pointer i integrated over the last Apply: force (N·s)
  /// and moment about pointer_origin(i) (N·m·s).
  const Wrench& pointer_impulse(std::size_t i = 0) const noexcept { return pointers_[i]->impulse; }

  const Vec3& pointer_origin(std::size_t i = 0) const noexcept { return pointers_[i]->origin; }

 private:
  // A touched object integrated over the step.
  struct LocalBody {
    int body = -1;
    double mass = 0.0;
    Mat3 inertia_B = Mat3::Identity();
    Vec3 p_BCm = Vec3::Zero();
    Quat q = Quat::Identity();
    Vec3 com = Vec3::Zero();
    Vec3 com0 = Vec3::Zero();
    Quat q0 = Quat::Identity();
    Vec3 v0 = Vec3::Zero();
    Vec3 w0 = Vec3::Zero();
    Vec3 v = Vec3::Zero();
    Vec3 w = Vec3::Zero();
    Vec3 a_other = Vec3::Zero();      // m/s², the rest of the world's, from the last step
    Vec3 alpha_other = Vec3::Zero();  // rad/s²
    Wrench impulse;                   // the proxy's, about com0
    Vec3 last_force = Vec3::Zero();   // the last substep's reaction force
    int local = -1;                   // index in solver_, or -1 (integrated here)
  };

  // What a body looked like before the previous step and what it was given then.
  struct BodyMemory {
    int body = -1;
    Vec3 v = Vec3::Zero();
    Vec3 w = Vec3::Zero();
    Wrench impulse;
  };

  // One pointer's physics-side proxy: its own IR builder (so the haptic IR's builder keeps its
  // state), renderer and IRs.
  struct PointerRun {
    PointerRun(world::World& world, int pointer_body, const settings::RenderingSettings& rendering,
               const render::ProxyRendererSettings& settings);
    GeometricIrBuilder builder;
    std::unique_ptr<ir::PhysicsSnapshot> snapshot = std::make_unique<ir::PhysicsSnapshot>();
    render::ProxyRenderer renderer;
    render::IrInterpolator interpolator;
    render::TickIr base;  // the newest IR at α = 1
    render::TickIr ir;    // re-posed for one substep
    render::ProxyOutput output;
    Wrench impulse;  // the proxy's wrench on the pointer over the last Apply
    Vec3 origin = Vec3::Zero();
  };

  void StartBodies(const world::World& world);
  void StartIsland();
  void EstimateOtherWrench(LocalBody* body) const;
  void PoseIr(PointerRun& run, const Pose& X_WP);
  void Substep(double h, std::span<const ir::HapticReport* const> reports, double t);
  Wrench ReactionOn(int body) const noexcept;
  Wrench DisplacementImpulse(const LocalBody& b) const;
  void Finish(world::World& world);
  LocalBody* Find(int body);

  world::ContactExporter exporter_;
  std::unique_ptr<ir::LocalContactModel> model_;
  render::LocalContactSolver solver_;
  std::vector<int> seeds_, motions_;
  bool island_touched_ = false;
  std::vector<std::unique_ptr<PointerRun>> pointers_;
  double physics_dt_;
  int substeps_;
  FixedVector<LocalBody, ir::kMaxNeighborBodies> bodies_;
  FixedVector<BodyMemory, ir::kMaxNeighborBodies> memory_;
  ir::HapticReport applied_;
  ir::HapticReport proxy_;
};

}  // namespace mrh::physics::internal
