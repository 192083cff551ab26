// SPDX-License-Identifier: Apache-2.0
// The worked example of docs/architecture.md, "Adding a method": "toy-plane" renders a spring to
// a fixed wall. examples/toy_method.cc runs it with the toy device of toy_line.h;
// tests/engine/toy_method_test.cc checks both in the build tree.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "mrh/core/spatial.h"
#include "mrh/core/status_bits.h"
#include "mrh/engine/method.h"
#include "mrh/haptic/method_haptic.h"
#include "mrh/ir/snapshot.h"
#include "mrh/physics/method_physics.h"
#include "mrh/world/world.h"

namespace toy {

// ---- The method's status bits: the enum and, beside it, its names. ----

/// TickOutput::status bits of the toy method's haptic half.
enum ToyPlaneStatusBits : std::uint32_t {
  kToyPlanePenetrating = 1u << 0,  ///< the pointer sphere is inside the wall this tick
};

inline constexpr std::array<mrh::StatusBitName, 1> kToyPlaneStatusNames{{
    {kToyPlanePenetrating, "penetrating"},
}};
static_assert(mrh::ValidStatusBitNames(kToyPlaneStatusNames));

/// The wall: the half-space x >= kWallX (m, world frame), its outward normal −x.
inline constexpr double kWallX = 0.05;

// ---- The haptic half: runs at 1 kHz, RT-safe, never sees the world. ----

/// Renders f = −k·d·x̂ for a pointer sphere of radius r (m) that reaches d = x + r − kWallX > 0
/// metres into the wall, with stiffness k (N/m). No torque and no reaction on the objects.
class ToyPlaneHaptic final : public mrh::haptic::MethodHaptic {
 public:
  ToyPlaneHaptic(double radius, double stiffness) : radius_(radius), k_(stiffness) {}

  void Adopt(const mrh::ir::PhysicsSnapshot&) noexcept override {}

  void HapticTick(const mrh::haptic::TickInput& in,
                  mrh::haptic::TickOutput* out) noexcept override {
    const double depth = in.X_WP.p.x() + radius_ - kWallX;
    out->w_W = mrh::Wrench{};
    out->contacts = 0;
    out->status = 0;
    if (depth <= 0.0) return;
    out->w_W.f = mrh::Vec3(-k_ * depth, 0.0, 0.0);
    out->contacts = 1;
    out->status = kToyPlanePenetrating;
  }

  // The engine fills the report's pointer pose; the wall pushes no object back.
  void EndPeriod(mrh::ir::HapticReport*) noexcept override {}

 private:
  double radius_;
  double k_;
};

// ---- The physics half: runs once per physics step and may use the world. ----

/// Moves the mocap pointer to the reported pose and steps the world; the snapshot carries only
/// the step's time (the haptic half needs nothing else).
class ToyPlanePhysics final : public mrh::physics::MethodPhysics {
 public:
  explicit ToyPlanePhysics(const mrh::physics::MethodContext& c)
      : world_(c.world), pointer_(c.pointer_body), physics_dt_(c.settings->physics_dt) {}

  void PhysicsStart(const mrh::ir::HapticReport& initial, mrh::ir::PhysicsSnapshot* out) override {
    world_->SetMocapPose(pointer_, initial.X_WP);
    out->step = -1;
    Stamp(out);
  }

  void PhysicsStep(const mrh::ir::HapticReport& report, mrh::ir::PhysicsSnapshot* out) override {
    world_->SetMocapPose(pointer_, report.X_WP);
    world_->Step();
    Stamp(out);
  }

 private:
  void Stamp(mrh::ir::PhysicsSnapshot* out) const {
    out->t = world_->time();
    out->physics_dt = physics_dt_;
  }

  mrh::world::World* world_;
  int pointer_;
  double physics_dt_;
};

// ---- The registration: one call. ----

/// Registers "toy-plane" (call once before the engine is built). The pointer radius is the
/// session's or the pointer's sphere geom (physics::PointerRadiusFor3Dof), the stiffness
/// rendering.stiffness.
inline void RegisterToyPlane() {
  mrh::engine::RegisterMethod(
      {"toy-plane",
       "Example: a spring to the fixed wall x >= 0.05 m, no reaction on the objects",
       {{"toy_plane", kToyPlaneStatusNames}},
       [](const mrh::physics::MethodContext& c) {
         mrh::engine::Method method;
         method.name = "toy-plane";
         method.physics = std::make_unique<ToyPlanePhysics>(c);
         method.haptic = std::make_unique<ToyPlaneHaptic>(mrh::physics::PointerRadiusFor3Dof(c),
                                                          c.settings->rendering.stiffness);
         return method;
       }});
}

}  // namespace toy
