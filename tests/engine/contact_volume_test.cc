// SPDX-License-Identifier: Apache-2.0
// Contact-volume penalty (B2, Hasegawa & Sato 2004) in lockstep under gravity, against closed
// forms: a face pressed to depth δ gives k δ whatever its area; a wedge gives the force and centre
// of pressure of its linear pressure; a stack rests at its weights over k; friction holds below μN
// and slides above it at g (sin α − μ cos α).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/device/simulated.h"
#include "mrh/engine/engine.h"
#include "mrh/world/world.h"

namespace mrh::engine {
namespace {

constexpr double kG = 9.81;
constexpr double kK = 1000.0;  // N/m

world::World PenaltyWorld(const std::string& bodies, bool penalty = true) {
  const std::string xml = fmt::format(R"(<mujoco>
  <option gravity="0 0 -{}"/>
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    {}
  </worldbody>
</mujoco>)",
                                      kG, bodies);
  return world::World::LoadString(
      xml, world::LoadOptions{.pointer_body = "pointer", .penalty_contacts = penalty});
}

settings::EngineSettings PenaltySettings(double duration, double damping, double friction) {
  settings::EngineSettings s;
  s.method = "contact-volume";
  s.mode = settings::Mode::kLockstep;
  s.physics_dt = 1e-3;
  s.haptic_dt = 1e-3;
  s.duration = duration;
  s.rendering.stiffness = kK;
  s.rendering.damping = damping;
  s.rendering.friction = friction;
  s.safety.ramp = false;
  s.realtime_priority = false;
  return s;
}

class Tap final : public physics::Recorder {
 public:
  explicit Tap(std::vector<int> bodies) : bodies_(std::move(bodies)) {}

  void OnTick(const ir::TickRecord& tick) override { ticks.push_back(tick); }

  void OnStep(const physics::StepRecord& step, const world::World& world) override {
    std::vector<Vec3> p;
    for (int b : bodies_) p.push_back(world.body_state(b).X_WB.p);
    times.push_back(step.t);
    positions.push_back(p);
  }

  std::vector<ir::TickRecord> ticks;
  std::vector<double> times;
  std::vector<std::vector<Vec3>> positions;

 private:
  std::vector<int> bodies_;
};

Tap RunPenalty(world::World world, const Pose& device_pose,
               const settings::EngineSettings& settings,
               const std::vector<std::string>& watched = {}) {
  std::vector<int> ids;
  for (const std::string& name : watched) ids.push_back(world.FindBody(name));
  device::Specifications specs;
  specs.max_force = 1000.0;
  Engine engine(std::move(world), device::MakeFixedDevice(device_pose, specs),
                device::Calibration{}, settings);
  Tap tap(ids);
  (void)engine.Run(&tap);
  return tap;
}

std::string PointerBox(double hx, double hy, double hz) {
  return fmt::format(
      R"(<body name="pointer" mocap="true" pos="0 0 1"><geom type="box" size="{} {} {}"/></body>)",
      hx, hy, hz);
}

// A mocap box pointer held with its bottom face δ below the floor: k·(V/A) = k δ, for a face of
// 4 cm × 4 cm and of 16 cm × 12 cm alike, with no torque about its centre.
TEST(ContactVolume, FacePressedToDepthGivesKDeltaWhateverItsArea) {
  constexpr double kDepth = 0.002, kHalfZ = 0.02;
  for (const auto& [hx, hy] : {std::pair{0.02, 0.02}, std::pair{0.08, 0.06}}) {
    const Pose pressed{Vec3(0.1, -0.2, kHalfZ - kDepth), Quat::Identity()};
    const Tap tap = RunPenalty(PenaltyWorld(PointerBox(hx, hy, kHalfZ)), pressed,
                               PenaltySettings(0.05, 0.0, 0.0));
    const Wrench& w = tap.ticks.back().displayed_W;
    EXPECT_NEAR(w.f.z(), kK * kDepth, 1e-9 * kK) << "face " << hx << " x " << hy;
    EXPECT_NEAR(w.f.head<2>().norm(), 0.0, 1e-9 * kK);
    EXPECT_NEAR(w.tau.norm(), 0.0, 1e-9 * kK * hx);
    EXPECT_EQ(tap.ticks.back().contacts, 1);
  }
}

// The box rotated by θ about y with its lowest edge δ below the floor: the overlap is a wedge of
// triangular section, edge at x_e, z = −δ, meeting the floor at x_e + δ tan θ and x_e − δ / tan θ.
// The pressure k h(x) is linear in x, so the force is k times the mean depth δ/2 and the centre
// of pressure the triangle's centroid (y = the box's), computed here from the corners.
TEST(ContactVolume, WedgeGivesTheForceAndCentreOfPressureOfALinearPressure) {
  constexpr double kA = 0.05, kB = 0.04, kC = 0.03, kTheta = 0.3, kDepth = 0.003;
  const Quat q(Eigen::AngleAxisd(kTheta, Vec3::UnitY()));
  const Vec3 corner = q * Vec3(kA, 0.0, -kC);  // the lowest edge, relative to the centre
  const Vec3 centre(0.2, 0.1, -kDepth - corner.z());
  const Tap tap = RunPenalty(PenaltyWorld(PointerBox(kA, kB, kC)), Pose{centre, q},
                             PenaltySettings(0.05, 0.0, 0.0));
  const double x_e = centre.x() + corner.x();
  const double x_cp = x_e + kDepth * (std::tan(kTheta) - 1.0 / std::tan(kTheta)) / 3.0;
  const Vec3 f(0.0, 0.0, kK * kDepth / 2.0);
  const Vec3 tau = (Vec3(x_cp, centre.y(), 0.0) - centre).cross(f);
  const Wrench& w = tap.ticks.back().displayed_W;
  EXPECT_NEAR((w.f - f).norm(), 0.0, 1e-6 * f.norm()) << w.f.transpose();
  EXPECT_NEAR((w.tau - tau).norm(), 0.0, 1e-6 * tau.norm())
      << w.tau.transpose() << " vs " << tau.transpose();
}

// Two 0.5 kg cubes stacked on the floor, the pointer far away: at rest each contact carries the
// weight above it, so the lower cube sinks (m1 + m2) g / k into the floor and the upper one
// m2 g / k into the lower (object–object contact, action = reaction). No lateral drift.
TEST(ContactVolume, StackRestsAtItsWeightsOverK) {
  constexpr double kMass = 0.5, kHalf = 0.05;
  const std::string cubes = fmt::format(
      R"(<body name="low" pos="0 0 {}"><freejoint/><geom type="box" size="{} {} {}" mass="{}"/></body>
         <body name="high" pos="0 0 {}"><freejoint/><geom type="box" size="{} {} {}" mass="{}"/></body>)",
      kHalf, kHalf, kHalf, kHalf, kMass, 3 * kHalf, kHalf, kHalf, kHalf, kMass);
  const Tap tap = RunPenalty(PenaltyWorld(cubes + PointerBox(0.02, 0.02, 0.02)),
                             Pose{Vec3(1.0, 1.0, 0.5), Quat::Identity()},
                             PenaltySettings(3.0, 30.0, 0.5), {"low", "high"});
  const std::vector<Vec3>& rest = tap.positions.back();
  const double sink_low = 2.0 * kMass * kG / kK, sink_high = kMass * kG / kK;
  constexpr double kTol = 1e-5;  // m: 0.2 % of the 4.9 mm sinks
  EXPECT_NEAR(rest[0].z(), kHalf - sink_low, kTol);
  EXPECT_NEAR(rest[1].z() - rest[0].z(), 2.0 * kHalf - sink_high, kTol);
  EXPECT_NEAR(rest[0].head<2>().norm(), 0.0, 1e-6);
  EXPECT_NEAR(rest[1].head<2>().norm(), 0.0, 1e-6);
  EXPECT_NEAR(tap.ticks.back().displayed_W.f.norm(), 0.0, 1e-12);  // the pointer touches nothing
}

// A flat 10 × 10 × 4 cm box on the floor under gravity tilted by α along x (μ = 0.5): with
// tan α = 0.25 friction holds it (it stops within the tangential spring's m g sin α / k); with
// tan α = 0.6 it slides with a = g (sin α − μ cos α). (Flat: the normalised pressure keeps its
// centre within a third of the half-width while the face stays in contact, and the friction's
// tipping moment needs 3 μ h / a = 0.6 of that.)
double SlideAcceleration(double tan_alpha, double* drift) {
  constexpr double kMass = 0.5, kHalf = 0.05, kHalfZ = 0.02, kMu = 0.5;
  world::World world = PenaltyWorld(
      fmt::format(
          R"(<body name="cube" pos="0 0 {}"><freejoint/><geom type="box" size="{} {} {}" mass="{}"/></body>)",
          kHalfZ - kMass * kG / kK, kHalf, kHalf, kHalfZ, kMass) +
      PointerBox(0.02, 0.02, 0.02));
  const double alpha = std::atan(tan_alpha);
  world.set_gravity(Vec3(kG * std::sin(alpha), 0.0, -kG * std::cos(alpha)));
  const Tap tap = RunPenalty(std::move(world), Pose{Vec3(1.0, 1.0, 0.5), Quat::Identity()},
                             PenaltySettings(2.0, 30.0, kMu), {"cube"});
  // x(t) at t = 1, 1.5, 2 s: a = (x(2) − 2 x(1.5) + x(1)) / 0.5².
  auto x_at = [&](double t) {
    for (std::size_t i = 0; i < tap.times.size(); ++i) {
      if (tap.times[i] >= t - 1e-9) return tap.positions[i][0].x();
    }
    return tap.positions.back()[0].x();
  };
  *drift = x_at(2.0) - x_at(1.0);
  return (x_at(2.0) - 2.0 * x_at(1.5) + x_at(1.0)) / 0.25;
}

TEST(ContactVolume, FrictionHoldsBelowMuNAndSlidesAboveIt) {
  double drift = 0.0;
  (void)SlideAcceleration(0.25, &drift);
  EXPECT_LT(std::abs(drift), 1e-5) << "the cube crept " << drift << " m in 1 s under tan α < μ";
  const double alpha = std::atan(0.6);
  const double expected = kG * (std::sin(alpha) - 0.5 * std::cos(alpha));
  const double a = SlideAcceleration(0.6, &drift);
  EXPECT_NEAR(a, expected, 0.02 * expected);
  EXPECT_GT(drift, 0.5 * expected);
}

TEST(ContactVolume, WorldWithMujocoContactsIsRefused) {
  try {
    (void)RunPenalty(PenaltyWorld(PointerBox(0.02, 0.02, 0.02), false), Pose{},
                     PenaltySettings(0.01, 0.0, 0.0));
    FAIL() << "a world with MuJoCo's contacts was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("penalty_contacts"), std::string::npos) << e.what();
  }
}

// physics_dt other than haptic_dt is forced to the haptic rate (single-rate), as single-rate is.
TEST(ContactVolume, RunsSingleRateWhateverPhysicsDtSays) {
  settings::EngineSettings s = PenaltySettings(0.01, 0.0, 0.0);
  s.physics_dt = 0.02;
  device::Specifications specs;
  specs.max_force = 1000.0;
  Engine engine(PenaltyWorld(PointerBox(0.02, 0.02, 0.02)), device::MakeFixedDevice(Pose{}, specs),
                device::Calibration{}, s);
  EXPECT_EQ(engine.settings().physics_dt, s.haptic_dt);
}

}  // namespace
}  // namespace mrh::engine
