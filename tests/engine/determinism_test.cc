// SPDX-License-Identifier: Apache-2.0
// Lockstep runs are bit-identical: a rerun matches, and the trace hashes to a golden constant.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>

#include "engine_test_util.h"
#include "mrh/device/simulated.h"
#include "support/hashing_recorder.h"

namespace mrh::engine::testing {
namespace {

using mrh::testing::HashingRecorder;

std::uint64_t RunAndHash(const char* method, const char* torque_model = "contact") {
  HashingRecorder recorder;
  settings::EngineSettings settings = T41Settings(method);
  settings.rendering.torque_model = *settings::ParseChoice<settings::TorqueModel>(torque_model);
  auto engine = T41Engine(settings);
  (void)engine->Run(&recorder);
  return recorder.hash();
}

// scenes/t3_6_push.xml pushed as scenes/t3_6_push.json does, for 2 s (the box is pushed from
// 1.25 s on).
std::uint64_t PushHash(const char* method) {
  settings::EngineSettings s;
  s.method = method;
  s.physics_dt = 0.02;
  s.duration = 2.0;
  s.rendering.stiffness = 2000.0;
  s.rendering.damping = 5.0;
  s.rendering.rot_stiffness = 20.0;
  s.rendering.rot_damping = 0.1;
  s.rendering.friction = 0.3;
  s.rendering.torque_model = settings::TorqueModel::kThesis;  // scenes/t3_6_push.json
  s.safety.ramp = false;
  s.realtime_priority = false;
  auto device = device::MakeScriptedDevice(
      {device::Keyframe{0.0, Pose{Vec3(-0.16, 0.0, 0.05), Quat::Identity()}},
       device::Keyframe{5.0, Pose{Vec3(0.24, 0.0, 0.05), Quat::Identity()}}});
  Engine engine(world::World::LoadFile(MRH_SOURCE_DIR "/scenes/t3_6_push.xml"), std::move(device),
                device::Calibration{}, s);
  HashingRecorder recorder;
  (void)engine.Run(&recorder);
  return recorder.hash();
}

TEST(DeterminismTest, LockstepRerunIsBitIdentical) {
  EXPECT_EQ(RunAndHash("impulse"), RunAndHash("impulse"));
  EXPECT_EQ(RunAndHash("single-rate"), RunAndHash("single-rate"));
}

TEST(DeterminismTest, LockstepTraceMatchesGoldenHash) {
  // Golden values of this build configuration family (g++ 12, -ffp-contract=off, x86-64 SSE2,
  // MuJoCo 3.14.0 from the pinned wheel). A change here means the simulation changed: review it,
  // then update. The T4.1 traces (one slide-jointed cube) have no box-floor contacts; the t3.6
  // box pushes do, so a MuJoCo upgrade may move those alone.
  EXPECT_EQ(RunAndHash("impulse"), 11173333966864450744ull);
  EXPECT_EQ(RunAndHash("single-rate"), 11100527457005068796ull);
  // proxy-6dof's default reaction on the pushed T4.1 cube is "local" (not the plain J/Δt,
  // rendering.proxy_reaction "impulse").
  EXPECT_EQ(RunAndHash("proxy-6dof", "thesis"), 15725993211209883540ull);
  // The default torque model, "contact": the touched cube receives the proxy's contact forces.
  EXPECT_EQ(RunAndHash("proxy-6dof"), 3454479041474762608ull);
  EXPECT_EQ(RunAndHash("local-dynamics"), 15579156835783394508ull);
  // T4.1's cube translates on three slides: the island simulates it in joint space (the island
  // of free bodies is pinned by the t3.6 face push below).
  EXPECT_EQ(RunAndHash("local-dynamics-6dof"), 11515530285661340936ull);
  // Pins the local solver's use of the scene's friction cone (t3_6_push.xml: pyramidal), the
  // renderer's wrench on island pairs (not the force at the f_k centre of pressure), and a
  // face–face pair's normal being the object face's own (not the minimal penetration direction).
  EXPECT_EQ(PushHash("local-dynamics-6dof"), 6295776439145346778ull);
  // proxy-6dof's "local" reaction through the box's contact island, its contacts warm-started
  // across steps.
  EXPECT_EQ(PushHash("proxy-6dof"), 3389059996476407888ull);
}

}  // namespace
}  // namespace mrh::engine::testing
