// SPDX-License-Identifier: Apache-2.0
// proxy-6dof on dynamic objects at physics_dt = 20 ms, against the 1 ms
// single-rate reference, with gravity, friction and resting contact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "engine/engine_impl.h"
#include "mrh/device/simulated.h"
#include "mrh/engine/engine.h"
#include "mrh/physics/physics_side.h"
#include "mrh/world/world.h"
#include "physics/proxy_physics.h"

namespace mrh::engine::testing {
namespace {

// The t3.6 box: 10 cm, 0.5 kg, μ 0.5 on the floor (scenes/t3_6_push.xml).
constexpr double kBoxMass = 0.5;
constexpr double kFloorMu = 0.5;
constexpr double kGravity = 9.81;
// Statistics window: the pointer reaches the box at 1.25 s; by 2 s the push is steady.
constexpr double kFrom = 2.0;
constexpr double kDuration = 5.0;

// scenes/t3_6_push.json: proxy-6dof, k_t 2000, d_t 5, k_r 20, d_r 0.1, friction 0.3.
settings::EngineSettings PushSettings(double physics_dt) {
  settings::EngineSettings s;
  s.method = "proxy-6dof";
  s.physics_dt = physics_dt;
  s.haptic_dt = 0.001;
  s.duration = kDuration;
  s.rendering.stiffness = 2000.0;
  s.rendering.damping = 5.0;
  s.rendering.rot_stiffness = 20.0;
  s.rendering.rot_damping = 0.1;
  s.rendering.friction = 0.3;
  // The thesis model of scenes/t3_6_push.json, whose bars these runs were set against.
  s.rendering.torque_model = settings::TorqueModel::kThesis;
  s.safety.ramp = false;
  s.realtime_priority = false;
  return s;
}

// The scripted pointer of scenes/t3_6_push.json, offset sideways by y (m).
std::unique_ptr<device::Device> PushDevice(double y) {
  return device::MakeScriptedDevice(
      {device::Keyframe{0.0, Pose{Vec3(-0.16, y, 0.05), Quat::Identity()}},
       device::Keyframe{kDuration, Pose{Vec3(0.24, y, 0.05), Quat::Identity()}}});
}

struct PushResult {
  double peak_v = 0.0;             // m/s, largest COM speed of any free body
  double peak_w = 0.0;             // rad/s, largest spin of any free body
  double contact_fraction = 0.0;   // ticks with contact in [kFrom, end]
  double mean_force_on_box = 0.0;  // N, applied reaction impulse / time in [kFrom, end]
};

// Counts the ticks with contact from kFrom on.
class ContactTap final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& t) override {
    if (t.t < kFrom) return;
    ++ticks;
    touching += t.contacts > 0 ? 1 : 0;
  }

  void OnStep(const physics::StepRecord&, const world::World&) override {}

  int ticks = 0;
  int touching = 0;
};

// Runs lockstep through the engine state so the applied reaction can be read per step.
PushResult RunPush(world::World world, double physics_dt, double y) {
  const settings::EngineSettings s = PushSettings(physics_dt);
  internal::EngineState state(std::move(world), PushDevice(y), device::Calibration{}, s);
  const int box = state.world.FindBody("box");
  std::vector<int> bodies;
  for (int b = 0; b < state.world.num_bodies(); ++b) {
    if (!state.world.body(b).is_static && !state.world.body(b).is_mocap) bodies.push_back(b);
  }
  ContactTap tap;
  physics::PhysicsSide physics = state.MakePhysicsSide(&tap);
  physics.Start(state.haptic->InitialReport(0.0));
  PushResult r;
  double box_impulse = 0.0;
  const auto steps = static_cast<std::int64_t>(std::llround(kDuration / physics_dt));
  std::int64_t tick = 0;
  for (std::int64_t k = 0; k < steps; ++k) {
    physics.Step(k);
    const ir::HapticReport* applied = state.method.physics->applied_reaction();
    if (applied != nullptr && state.world.time() > kFrom) {
      for (const ir::BodyImpulse& j : applied->impulses) {
        if (j.body == box) box_impulse += j.linear.x();
      }
    }
    for (const int b : bodies) {
      const world::BodyState st = state.world.body_state(b);
      r.peak_v = std::max(r.peak_v, st.V_WCm.v.norm());
      r.peak_w = std::max(r.peak_w, st.V_WCm.w.norm());
    }
    for (int j = 0; j < state.ticks_per_step; ++j, ++tick) {
      state.haptic->Tick(static_cast<double>(tick) * s.haptic_dt);
    }
    physics.TakeReports();
    physics.Publish();
    physics.DrainTickRecords();
  }
  r.contact_fraction = tap.ticks > 0 ? static_cast<double>(tap.touching) / tap.ticks : 0.0;
  r.mean_force_on_box = box_impulse / (kDuration - kFrom);
  return r;
}

world::World PushWorld() {
  return world::World::LoadFile(MRH_SOURCE_DIR "/scenes/t3_6_push.xml");
}

// Acceptance bars: proxy-6dof at 20 ms does not fling objects (peak speed below 2× the
// reference's); the spin bar is local-dynamics-6dof's, peak spin at most the reference's
// + 1 rad/s. "Contact kept most of the time": at
// least 90 % of the ticks after the push has settled. The box slides at a steady mean speed,
// so the reaction it receives must average the floor's kinetic friction μ m g (within 10 %).
TEST(ProxyDynamicTest, BoxPushAt20MsStaysWithinReachOfThe1MsReference) {
  const PushResult reference = RunPush(PushWorld(), 0.001, 0.0);
  const PushResult run = RunPush(PushWorld(), 0.02, 0.0);
  EXPECT_LT(run.peak_v, 2.0 * reference.peak_v) << "reference " << reference.peak_v;
  EXPECT_LT(run.peak_w, reference.peak_w + 1.0) << "reference " << reference.peak_w;
  EXPECT_GE(run.contact_fraction, 0.9);
  const double friction = kFloorMu * kBoxMass * kGravity;
  EXPECT_NEAR(run.mean_force_on_box, friction, 0.1 * friction);
}

// A centred face push spins nothing: its peak spin at 20 ms stays below half of what an
// off-centre push (4 cm to the side of the 10 cm box) legitimately gives in the 1 ms reference.
// At 4 cm the pointer face lies wholly on one side of the centre line, so the push must turn
// the box (the thesis torque model's couple slows the turn: peak 0.5 rad/s); at 3 cm its edge
// is on the line and whether it turns is a bifurcation.
TEST(ProxyDynamicTest, CentredFacePushSpinsNothingAgainstAnOffCentrePush) {
  const PushResult off_centre = RunPush(PushWorld(), 0.001, 0.04);
  const PushResult centred = RunPush(PushWorld(), 0.02, 0.0);
  EXPECT_LT(centred.peak_w, 0.5 * off_centre.peak_w);
}

// The T3.3 kind of push: the box pointer pushes a row of three 10 cm, 0.5 kg cubes on a floor
// (μ 0.5). Bounded: no cube faster than 2× the 1 ms reference's fastest (the acceptance bar).
world::World RowWorld() {
  return world::World::LoadString(R"(<mujoco><option timestep="0.02" gravity="0 0 -9.81"/>
    <default><geom condim="3" friction="0.5 0.005 0.0001"/></default><worldbody>
    <geom name="floor" type="plane" size="3 3 0.1"/>
    <body name="box" pos="0 0 0.05"><freejoint/>
      <geom type="box" size="0.05 0.05 0.05" mass="0.5"/></body>
    <body name="box2" pos="0.101 0 0.05"><freejoint/>
      <geom type="box" size="0.05 0.05 0.05" mass="0.5"/></body>
    <body name="box3" pos="0.202 0 0.05"><freejoint/>
      <geom type="box" size="0.05 0.05 0.05" mass="0.5"/></body>
    <body name="pointer" mocap="true" pos="-0.16 0 0.05">
      <geom type="box" size="0.01 0.03 0.02" density="1000" contype="0" conaffinity="0"/>
    </body></worldbody></mujoco>)");
}

// The acceptance bar for proxy-6dof at 20 ms (does not fling: below 2× the reference's) on
// speed and spin; the cubes of the reference row themselves turn (~6.5 rad/s) as they collide.
TEST(ProxyDynamicTest, RowOfThreeCubesPushedAt20MsStaysBounded) {
  const PushResult reference = RunPush(RowWorld(), 0.001, 0.0);
  const PushResult run = RunPush(RowWorld(), 0.02, 0.0);
  EXPECT_LT(run.peak_v, 2.0 * reference.peak_v) << "reference " << reference.peak_v;
  EXPECT_LT(run.peak_w, 2.0 * reference.peak_w) << "reference " << reference.peak_w;
}

// Per step, in zero gravity with nothing else touching the box (an off-centre push, so the
// reaction has torque): the world's box gains exactly the reported applied linear impulse; the
// physics-side proxy's reaction on the box and its wrench on the pointer (springs only) cancel in
// linear and angular momentum about one common point (the pointer origin); the run's totals are the
// sum of what was applied.
TEST(ProxyDynamicTest, AppliedReactionIsReportedAndTheProxysActionEqualsReaction) {
  world::World w = world::World::LoadString(R"(<mujoco><option timestep="0.02" gravity="0 0 0"/>
    <worldbody><body name="box" pos="0 0 0.05"><freejoint/>
      <geom type="box" size="0.05 0.05 0.05" mass="0.5"/></body>
    <body name="pointer" mocap="true" pos="-0.16 0 0.05">
      <geom type="box" size="0.01 0.03 0.02" density="1000" contype="0" conaffinity="0"/>
    </body></worldbody></mujoco>)");
  // Springs only: with dampers, the tick a contact ends renders d·(0 − Δr_prev)/dt to the
  // pointer while its pair (now without rows) gets no reaction (a ProxyRenderer property).
  settings::EngineSettings s = PushSettings(0.02);
  s.rendering.damping = 0.0;
  s.rendering.rot_damping = 0.0;
  internal::EngineState state(std::move(w), PushDevice(0.03), device::Calibration{}, s);
  const auto* method =
      dynamic_cast<const physics::internal::ProxyPhysics*>(state.method.physics.get());
  ASSERT_NE(method, nullptr);
  ASSERT_NE(method->local_reaction(), nullptr) << "the default reaction is not \"local\"";
  const physics::internal::ProxyLocalReaction& local = *method->local_reaction();
  const int box = state.world.FindBody("box");
  physics::PhysicsSide physics = state.MakePhysicsSide(nullptr);
  physics.Start(state.haptic->InitialReport(0.0));
  Vec3 applied_total = Vec3::Zero();
  int touched = 0;
  std::int64_t tick = 0;
  for (std::int64_t k = 0; k < 150; ++k) {
    const world::BodyState before = state.world.body_state(box);
    physics.Step(k);
    const world::BodyState after = state.world.body_state(box);
    Wrench applied, proxy;
    for (const ir::BodyImpulse& j : local.applied().impulses) applied = {j.linear, j.angular};
    for (const ir::BodyImpulse& j : local.proxy_impulses().impulses) proxy = {j.linear, j.angular};
    applied_total += applied.f;
    touched += applied.f.isZero(0.0) ? 0 : 1;
    const double scale = 1e-9 * std::max(1e-3, proxy.f.norm() + proxy.tau.norm());
    const Vec3 dp = kBoxMass * (after.V_WCm.v - before.V_WCm.v);
    EXPECT_LT((dp - applied.f).norm(), 1e-9 * std::max(1e-3, applied.f.norm())) << "step " << k;
    const Wrench& P = local.pointer_impulse();
    const Vec3 o = local.pointer_origin();
    EXPECT_LT((proxy.f + P.f).norm(), scale) << "step " << k;
    EXPECT_LT((proxy.tau + (before.p_WCm - o).cross(proxy.f) + P.tau).norm(), scale)
        << "step " << k;
    for (int j = 0; j < state.ticks_per_step; ++j, ++tick) {
      state.haptic->Tick(static_cast<double>(tick) * 0.001);
    }
    physics.TakeReports();
    physics.Publish();
    physics.DrainTickRecords();
  }
  EXPECT_GE(touched, 3) << "the pointer hardly touched the box";
  physics::PhysicsStats stats;
  physics.Finish(&stats);
  ASSERT_EQ(stats.impulses.size(), 1u);
  EXPECT_LT((stats.impulses[0].linear - applied_total).norm(), 1e-9 * applied_total.norm());
}

}  // namespace
}  // namespace mrh::engine::testing
