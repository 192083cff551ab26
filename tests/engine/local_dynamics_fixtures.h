// SPDX-License-Identifier: Apache-2.0
// Shared fixtures of the local-dynamics tests: scenes, settings, a pushing device and lockstep
// periods run by hand.
#pragma once

#include <memory>
#include <string>

#include "engine/engine_impl.h"
#include "haptic/local_dynamics_haptic.h"
#include "mrh/device/simulated.h"
#include "physics/local_dynamics_physics.h"

namespace mrh::engine::testing {

using haptic::internal::LocalDynamicsHaptic;
using internal::EngineState;
using internal::PhysicsSide;
using physics::internal::LocalDynamicsPhysics;

// A free 2 kg box, turned, in zero gravity, with a pointer 1 cm off its +x face, away from the
// face centre so that a push also turns it.
inline constexpr char kFreeBox[] = R"(
<mujoco>
  <option timestep="0.05" gravity="0 0 0"/>
  <worldbody>
    <body name="box" pos="0 0 0" euler="0 0 20"><freejoint/>
      <geom type="box" size="0.05 0.1 0.15" mass="2"/></body>
    <body name="pointer" mocap="true" pos="0.08 0.05 0.07">
      <geom type="sphere" size="0.02" contype="0" conaffinity="0"/></body>
  </worldbody>
</mujoco>)";

// A 1 kg cube on a floor with friction, and a pointer 1 cm from its −x face at COM height. The
// cube starts just touching and first settles 0.36 mm into MuJoCo's soft contact: a bounce the
// local simulation must follow without going unstable.
inline constexpr char kCubeOnFloor[] = R"(
<mujoco>
  <option timestep="0.05" gravity="0 0 -9.81"/>
  <worldbody>
    <geom name="floor" type="plane" size="3 3 0.1" friction="0.5 0.005 0.0001"/>
    <body name="cube" pos="0 0 0.05"><freejoint/>
      <geom type="box" size="0.05 0.05 0.05" mass="1" friction="0.5 0.005 0.0001"/></body>
    <body name="pointer" mocap="true" pos="-0.08 0 0.05">
      <geom type="sphere" size="0.02" contype="0" conaffinity="0"/></body>
  </worldbody>
</mujoco>)";

inline settings::EngineSettings LocalSettings(double duration, const char* model = "perturbation") {
  settings::EngineSettings s;
  s.method = "local-dynamics";
  s.physics_dt = 0.05;
  s.haptic_dt = 0.001;
  s.duration = duration;
  s.pointer.radius = 0.02;
  s.rendering.stiffness = 1000.0;
  // Most tests check the thesis model (eq. 4.16–4.18 with A, b); the rest and synchronization
  // tests also run the contact model.
  s.rendering.local_model = *settings::ParseChoice<settings::LocalModel>(model);
  s.safety.ramp = false;
  s.realtime_priority = false;
  return s;
}

// A pointer moving from p0 at `speed` along +x for the whole run (scripted: the user is an
// infinitely stiff hand, as in T4.1).
inline std::unique_ptr<device::Device> PushingDevice(const Vec3& p0, double speed,
                                                     double duration) {
  device::Specifications specs;
  specs.max_force = 100.0;
  return device::MakeScriptedDevice(
      {{0.0, Pose{p0, Quat::Identity()}},
       {duration, Pose{p0 + Vec3(speed * duration, 0, 0), Quat::Identity()}}},
      specs);
}

inline const ir::BodyMotion* MotionOf(const ir::PhysicsSnapshot& snapshot, int body) {
  for (const ir::BodyMotion& m : snapshot.bodies) {
    if (m.body == body) return &m;
  }
  return nullptr;
}

// Runs lockstep periods of `state` by hand (as RunLockstep does), calling `on_tick` after every
// haptic tick.
template <typename OnTick>
void RunPeriods(EngineState& state, int periods, OnTick on_tick) {
  PhysicsSide physics = state.MakePhysicsSide(nullptr);
  physics.Start(state.haptic->InitialReport(0.0));
  std::int64_t tick = 0;
  for (int k = 0; k < periods; ++k) {
    physics.Step(k);
    for (int j = 0; j < state.ticks_per_step; ++j, ++tick) {
      state.haptic->Tick(static_cast<double>(tick) * state.settings.haptic_dt);
      on_tick(k, j);
    }
    physics.TakeReports();
    physics.Publish();
    physics.DrainTickRecords();
  }
}

// The two halves of the state's local-dynamics method.
inline const LocalDynamicsPhysics& PhysicsOf(EngineState& state) {
  return *static_cast<const LocalDynamicsPhysics*>(state.method.physics.get());
}

inline const LocalDynamicsHaptic& HapticOf(EngineState& state) {
  return *static_cast<const LocalDynamicsHaptic*>(state.method.haptic.get());
}

}  // namespace mrh::engine::testing
