// SPDX-License-Identifier: Apache-2.0
// Virtual coupling (B3, Colgate et al. 1995): the tool's inertia is felt in free motion (−m_t ẍ_t
// against the tool's linear steady state), and pressed into a floor the force settles at the
// spring's.
#include "mrh/render/virtual_coupling.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/device/simulated.h"
#include "mrh/engine/engine.h"
#include "mrh/physics/methods.h"
#include "mrh/world/world.h"

namespace mrh::engine {
namespace {

constexpr double kMass = 0.5;   // tool mass (kg)
constexpr double kHalf = 0.05;  // tool box half side (m)
constexpr double kK = 1000.0;   // coupling spring (N/m)
constexpr double kB = 10.0;     // coupling damper (N·s/m)
constexpr double kDt = 1e-3;    // haptic = physics period (s)

// Under gravity: a floor plane and a box pointer (mocap in the file; the method makes it free).
constexpr char kScene[] = R"(<mujoco>
  <option gravity="0 0 -9.81"/>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="pointer" mocap="true" pos="0 0 0.5">
      <geom type="box" size="0.05 0.05 0.05" mass="0.5"/>
    </body>
  </worldbody>
</mujoco>)";

// `xml` in a temporary file of this process, removed with the object (ctest runs the tests of
// this file in parallel processes: a shared name let one truncate the scene another loaded).
struct TempScene {
  TempScene(const std::string& stem, const char* xml)
      : path(std::filesystem::temp_directory_path() /
             (stem + "_" + std::to_string(::getpid()) + ".xml")) {
    std::ofstream(path) << xml;
  }

  ~TempScene() { std::filesystem::remove(path); }

  TempScene(const TempScene&) = delete;
  TempScene& operator=(const TempScene&) = delete;
  std::filesystem::path path;
};

world::World ToolWorld() {
  const TempScene file("mrh_virtual_coupling_test", kScene);
  return world::World::LoadFile(
      file.path, world::LoadOptions{.pointer_body = "pointer", .dynamic_pointer = true});
}

settings::EngineSettings CouplingSettings(double duration) {
  settings::EngineSettings s;
  s.method = "virtual-coupling";
  s.mode = settings::Mode::kLockstep;
  s.physics_dt = kDt;
  s.haptic_dt = kDt;
  s.duration = duration;
  s.rendering.coupling_stiffness = kK;
  s.rendering.coupling_damping = kB;
  s.safety.ramp = false;
  s.realtime_priority = false;
  return s;
}

class Tap final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& tick) override { ticks.push_back(tick); }

  void OnStep(const physics::StepRecord&, const world::World&) override {}

  std::vector<ir::TickRecord> ticks;
};

std::vector<ir::TickRecord> RunCoupled(std::vector<device::Keyframe> keyframes, double duration) {
  device::Specifications specs;
  specs.max_force = 1000.0;
  Engine engine(ToolWorld(), device::MakeScriptedDevice(std::move(keyframes), specs),
                device::Calibration{}, CouplingSettings(duration));
  Tap tap;
  (void)engine.Run(&tap);
  return tap.ticks;
}

TEST(VirtualCoupling, FreeMotionDisplaysTheToolInertia) {
  constexpr double kAmplitude = 0.05, kHz = 2.0, kDuration = 2.0;
  const double omega = 2.0 * std::numbers::pi * kHz;
  std::vector<device::Keyframe> keyframes;
  for (int i = 0; i <= static_cast<int>(kDuration / kDt) + 1; ++i) {
    const double t = i * kDt;
    keyframes.push_back(
        {t, Pose{Vec3(kAmplitude * std::sin(omega * t), 0.0, 0.5), Quat::Identity()}});
  }
  const std::vector<ir::TickRecord> ticks = RunCoupled(keyframes, kDuration);
  // Linear steady state of m ẍ_t = k (x_h − x_t) + b (ẋ_h − ẋ_t) for x_h = A sin ωt:
  // x_t = Im(H A e^{iωt}), H = (k + ibω) / (k − mω² + ibω); displayed −F_c = −m ẍ_t = mω² x_t.
  const std::complex<double> ib(0.0, kB * omega);
  const std::complex<double> H = (kK + ib) / (kK - kMass * omega * omega + ib);
  const std::complex<double> expected = kMass * omega * omega * H * kAmplitude;
  // Complex amplitude of the displayed f_x over the last whole second (2 periods; the
  // transient decays with 2m/b = 0.1 s).
  std::complex<double> measured = 0.0;
  int n = 0;
  for (const ir::TickRecord& tick : ticks) {
    if (tick.t < 1.0 - 1e-9) continue;
    measured += tick.displayed_W.f.x() *
                std::complex<double>(std::sin(omega * tick.t), std::cos(omega * tick.t));
    ++n;
  }
  ASSERT_GT(n, 900);
  measured *= 2.0 / n;  // f = Im(c e^{iωt}) = Re(c) sin + Im(c) cos
  EXPECT_LE(std::abs(measured - expected), 0.02 * std::abs(expected))
      << "measured " << measured << " expected " << expected;
  // The weight is compensated: no vertical force in free motion.
  EXPECT_NEAR(ticks.back().displayed_W.f.z(), 0.0, 0.01 * std::abs(expected));
}

TEST(VirtualCoupling, PressingIntoAFloorSettlesAtTheSpringForce) {
  constexpr double kPress = 0.01;  // device held 1 cm below the tool's resting height
  const Pose above{Vec3(0.0, 0.0, kHalf + 0.02), Quat::Identity()};
  const Pose pressed{Vec3(0.0, 0.0, kHalf - kPress), Quat::Identity()};
  const std::vector<ir::TickRecord> ticks = RunCoupled({{0.0, above}, {0.5, pressed}}, 2.0);
  const ir::TickRecord& last = ticks.back();
  // The tool rests on the floor (MuJoCo's soft contact: < 1 mm in) ...
  const double z_tool = last.X_WQ.p.z();
  EXPECT_NEAR(z_tool, kHalf, 1e-3);
  // ... and the hand feels the coupling spring's stretch, k (z_t − z_h), pushing up.
  EXPECT_NEAR(last.displayed_W.f.z(), kK * (z_tool - pressed.p.z()), 1e-3 * kK * kPress);
  EXPECT_NEAR(last.displayed_W.f.z(), kK * kPress, 0.1 * kK * kPress);
  // Settled: the last 100 ms vary by less than 1 %.
  double lo = 1e9, hi = -1e9;
  for (std::size_t i = ticks.size() - 100; i < ticks.size(); ++i) {
    lo = std::min(lo, ticks[i].displayed_W.f.z());
    hi = std::max(hi, ticks[i].displayed_W.f.z());
  }
  EXPECT_LT(hi - lo, 0.01 * kK * kPress);
}

TEST(VirtualCoupling, MocapPointerWorldIsRefusedWithTheFix) {
  EXPECT_THROW(
      {
        const TempScene file("mrh_virtual_coupling_mocap", kScene);
        Engine engine(world::World::LoadFile(file.path), device::MakeFixedDevice(Pose{}),
                      device::Calibration{}, CouplingSettings(0.1));
      },
      mrh::Error);
}

// A light sphere tool (r 1.5 cm, water density: m = 14.1 g, I = 2/5 m r² = 1.27e-6 kg·m²), as in
// scenes/demo.json, pressed 1 cm into the floor and dragged 5 cm along it (friction turns it).
// Its geom collides with nothing, as IR-based pointers' geoms do: the tool must collide anyway.
constexpr char kLightScene[] = R"(<mujoco>
  <option gravity="0 0 -9.81"/>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="pointer" mocap="true" pos="0 0 0.1">
      <geom type="sphere" size="0.015" density="1000" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
</mujoco>)";

RunStats RunLightTool(const settings::RenderingSettings& rendering) {
  const TempScene file("mrh_virtual_coupling_light", kLightScene);
  settings::EngineSettings s = CouplingSettings(1.0);
  s.rendering = rendering;
  device::Specifications specs;
  specs.max_force = 1000.0;
  Engine engine(world::World::LoadFile(file.path, world::LoadOptions{.pointer_body = "pointer",
                                                                     .dynamic_pointer = true}),
                device::MakeScriptedDevice({{0.0, Pose{Vec3(0.0, 0.0, 0.1), Quat::Identity()}},
                                            {0.3, Pose{Vec3(0.0, 0.0, 0.005), Quat::Identity()}},
                                            {1.0, Pose{Vec3(0.05, 0.0, 0.005), Quat::Identity()}}},
                                           specs),
                device::Calibration{}, s);
  return engine.Run(nullptr);
}

// The light tool: a 1.5 cm sphere of density 1000, I = 0.4 m r² about every axis.
constexpr double kLightRadius = 0.015;
const double kLightMass = 1000.0 * 4.0 / 3.0 * std::numbers::pi * std::pow(kLightRadius, 3);
const double kLightInertia = 0.4 * kLightMass * kLightRadius * kLightRadius;

// Unset rotational gains come from the tool: k_r = k I/m = k · 0.4 r², b_r = b · 0.4 r² (the
// translational a = k h²/m and c = b h/m on the rotation), computed here from the sphere.
TEST(VirtualCoupling, UnsetRotationalGainsFollowTheToolInertia) {
  const TempScene file("mrh_virtual_coupling_gains", kLightScene);
  world::World world = world::World::LoadFile(
      file.path, world::LoadOptions{.pointer_body = "pointer", .dynamic_pointer = true});
  settings::EngineSettings s = CouplingSettings(1.0);
  const physics::MethodContext context{
      .world = &world, .settings = &s, .pointer_body = world.FindBody("pointer")};
  const render::CouplingGains g = physics::ResolveCouplingGains(context);
  EXPECT_EQ(g.k, kK);
  EXPECT_EQ(g.b, kB);
  EXPECT_NEAR(g.k_r, kK * kLightInertia / kLightMass, 1e-9 * g.k_r);
  EXPECT_NEAR(g.b_r, kB * kLightInertia / kLightMass, 1e-9 * g.b_r);
  s.rendering.coupling_rot_stiffness = 0.5;  // given gains are kept
  s.rendering.coupling_rot_damping = 0.0;
  const render::CouplingGains given = physics::ResolveCouplingGains(context);
  EXPECT_EQ(given.k_r, 0.5);
  EXPECT_EQ(given.b_r, 0.0);
}

// The old fixed rotational gains (1 N·m/rad, 0.01 N·m·s/rad) on this tool: a_r = k_r h²/I = 0.79,
// c_r = b_r h/I = 7.9, far outside the stable loop (MuJoCo resets the tool with "bad number in
// qacc"): refused at setup, naming the key. With the gains unset (the default) the tool's own
// gains run without a warning, and pressed 1 cm below the resting tool the force is about the
// coupling spring's k·0.01 = 10 N, not a blow-up.
TEST(VirtualCoupling, UnstableGainsForALightToolAreRefusedAndTheDefaultsRun) {
  settings::RenderingSettings fixed;
  fixed.coupling_rot_stiffness = 1.0;
  fixed.coupling_rot_damping = 0.01;
  try {
    (void)RunLightTool(fixed);
    FAIL() << "unstable rotational coupling accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("rendering.coupling_rot_stiffness = 1 "),
              std::string::npos)
        << e.what();
  }
  const settings::RenderingSettings defaults;
  ASSERT_FALSE(defaults.coupling_rot_stiffness.has_value());
  const RunStats stats = RunLightTool(defaults);
  EXPECT_TRUE(stats.warnings.empty()) << stats.warnings.front();
  EXPECT_EQ(stats.fault_nonfinite_wrench, 0);
  EXPECT_LT(stats.max_force, 2.0 * defaults.coupling_stiffness * 0.01);
}

// Pressed 1 cm below the resting light tool, the force is about the coupling spring's k·0.01 =
// 10 N. (MuJoCo 3's broadphase tests per-body collision masks: a tool whose geoms are made to
// collide after compilation, without updating them, falls through the floor and feels 3.6 N.)
TEST(VirtualCoupling, PressedLightToolFeelsTheCouplingSpring) {
  const settings::RenderingSettings defaults;
  const RunStats stats = RunLightTool(defaults);
  EXPECT_GT(stats.max_force, 0.5 * defaults.coupling_stiffness * 0.01);
}

}  // namespace
}  // namespace mrh::engine
