// SPDX-License-Identifier: Apache-2.0
// t3.7: the bars by which runs are judged (Judge), and the essential result on a sphere, an
// upright cylinder, an ellipsoid, a convex mesh and a compound body pushed by the box pointer:
// against mechanics (nothing thrown, the sphere rolls at v / r, a steady slide costs μ m g) and
// against the tool as a rigid MuJoCo body at 1 ms (the compound body turns the reference's way;
// the cylinder, deflected by the pointer's edge, and the mesh, pushed on one end of its face,
// take the reference's impulse and go where it goes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "experiment_test_util.h"
#include "experiments/experiments_impl.h"

namespace mrh::experiments::internal {
namespace {

T37Result Made(const char* method, double peak_speed) {
  T37Result r;
  r.method = method;
  r.peak_speed = peak_speed;
  return r;
}

TEST(T37JudgeTest, SpeedBarIsTheLargerOfThePushAndTheReference) {
  const T37Result ref = Made("virtual-coupling@1ms", 0.05);
  EXPECT_FALSE(Judge(Made("x", 0.24), ref).thrown);  // below 2.5 × 0.1 m/s
  EXPECT_TRUE(Judge(Made("x", 0.26), ref).thrown);
  // An ellipsoid that rolls over gains speed from gravity: the reference's peak sets the bar.
  const T37Result egg = Made("virtual-coupling@1ms", 0.4);
  EXPECT_FALSE(Judge(Made("x", 0.9), egg).thrown);
  EXPECT_TRUE(Judge(Made("x", 1.1), egg).thrown);
}

TEST(T37JudgeTest, RollingBodiesHaveSpinBarsButNoPositionOrForceBars) {
  T37Result ref = Made("virtual-coupling@1ms", 0.1);
  ref.rolling_radius = 0.04;
  ref.offcentre = true;
  T37Result r = ref;
  r.peak_spin = 0.1 / 0.04 * 2.4;
  r.end = Vec3(1.0, 1.0, 0.0);  // far from the reference: it rolled away after its kick
  T37Verdict v = Judge(r, ref);
  EXPECT_FALSE(v.spun);
  EXPECT_FALSE(v.pose_error.has_value());
  EXPECT_FALSE(v.force_vs_ref.has_value());
  r.peak_spin = 0.1 / 0.04 * 2.6;
  EXPECT_TRUE(Judge(r, ref).spun);
}

TEST(T37JudgeTest, OffCentreSlidersFollowTheReferenceImpulseAndTurn) {
  T37Result ref = Made("virtual-coupling@1ms", 0.1);
  ref.offcentre = true;
  ref.impulse = Vec3(-4.0, 2.0, 0.0);
  ref.yaw = -1.0;
  T37Result r = ref;
  r.impulse = Vec3(-4.0, 2.0 + 0.09 * std::hypot(4.0, 2.0), 0.0);
  r.end = Vec3(0.0, 0.019, 0.0);
  T37Verdict v = Judge(r, ref);
  ASSERT_TRUE(v.follows_ref.has_value());
  EXPECT_TRUE(*v.follows_ref);
  EXPECT_NEAR(*v.force_vs_ref, 0.09, 1e-12);
  ASSERT_TRUE(v.same_turn.has_value());
  EXPECT_TRUE(*v.same_turn);
  r.yaw = 0.5;
  r.end = Vec3(0.0, 0.021, 0.0);
  v = Judge(r, ref);
  EXPECT_FALSE(*v.same_turn);
  EXPECT_FALSE(*v.follows_ref);
  // A body held straight does not turn the reference's way, whatever the sign of its yaw.
  r.yaw = -0.01;
  EXPECT_FALSE(*Judge(r, ref).same_turn);
  // A reference that barely turned sets no direction.
  ref.yaw = 0.01;
  EXPECT_FALSE(Judge(r, ref).same_turn.has_value());
}

TEST(T37JudgeTest, SteadySlideWithinFivePercentOfCoulomb) {
  T37Result r = Made("x", 0.1);
  r.coulomb_f = 2.0;
  r.mean_f = 2.09;
  EXPECT_TRUE(*Judge(r, r).slide_ok);
  r.mean_f = 1.89;
  EXPECT_FALSE(*Judge(r, r).slide_ok);
}

const T37Result& Find(const std::vector<T37Result>& runs, const std::string& shape, bool offcentre,
                      const std::string& method) {
  for (const T37Result& r : runs) {
    if (r.shape == shape && r.offcentre == offcentre && r.method == method) return r;
  }
  throw std::runtime_error("no run " + shape + " " + method);
}

TEST(T37Test, SphereCylinderEllipsoidAndCompoundUnderTheBoxPointer) {
  const std::filesystem::path out = testing::TempDir("mrh_t3_7_test_");
  T37Options options;
  options.shapes = {"sphere", "cylinder", "ellipsoid", "mesh", "compound"};
  const std::vector<T37Result> runs = RunT37Cases(out, /*quiet=*/true, options);
  std::filesystem::remove_all(out);
  ASSERT_EQ(runs.size(), 5u * 2u * 4u);
  constexpr double kV = 0.1;  // m/s, the push
  const char* ld = "local-dynamics-6dof@20ms";
  for (std::size_t i = 0; i < runs.size(); i += 4) {
    const T37Result& ref = runs[i];
    ASSERT_EQ(ref.method, "virtual-coupling@1ms");
    EXPECT_GT(ref.end.x(), 0.03) << ref.shape << ": the reference never pushed";
    for (std::size_t k = 1; k < 4; ++k) {
      // Nothing is thrown, by any method (proxy-6dof at 20 ms included): 2.5 v, or 2.5 times
      // the reference's peak where gravity speeds the body (the ellipsoid rolling over).
      EXPECT_LT(runs[i + k].peak_speed, 2.5 * std::max(kV, ref.peak_speed))
          << ref.shape << " " << runs[i + k].method;
    }
  }
  for (const char* method : {ld, "proxy-6dof@1ms"}) {
    for (const bool off : {false, true}) {
      const T37Result& ball = Find(runs, "sphere", off, method);
      EXPECT_LT(ball.peak_spin, 2.5 * kV / 0.04) << method;
      EXPECT_GT(ball.end.x(), 0.3) << method << ": the sphere did not roll ahead";
    }
    // Steady slides: Coulomb's μ m g (0.5 × 0.3 kg and 0.5 × 0.5 kg at 9.81 m/s²).
    for (const char* shape : {"cylinder", "mesh"}) {
      const T37Result& slide = Find(runs, shape, false, method);
      EXPECT_NEAR(slide.coulomb_f, 0.5 * 0.3 * 9.81, 1e-4) << shape;  // the mesh feet weigh 6 mg
      EXPECT_NEAR(slide.mean_f, slide.coulomb_f, 0.05 * slide.coulomb_f) << shape << " " << method;
    }
    // And feel steady: no more force fluctuation than the rigid tool's (an object's edge on the
    // pointer face, a compound's two faces).
    for (const char* shape : {"cylinder", "mesh", "compound"}) {
      const T37Result& slide = Find(runs, shape, false, method);
      const T37Result& ref = Find(runs, shape, false, "virtual-coupling@1ms");
      EXPECT_LE(slide.sd_f, ref.sd_f) << shape << " " << method;
    }
  }
  // The ellipsoid pushed off centre tips, turns and stops: the local island's floor contact
  // must follow its support point as it rocks, or it is launched (0.59 m/s, ends 44 cm away).
  const T37Result& egg_ref = Find(runs, "ellipsoid", true, "virtual-coupling@1ms");
  const T37Result& egg = Find(runs, "ellipsoid", true, ld);
  EXPECT_LT((egg.end - egg_ref.end).head<2>().norm(), 0.02);
  const T37Result& compound = Find(runs, "compound", false, ld);
  EXPECT_NEAR(compound.mean_f, 0.5 * 0.5 * 9.81, 0.05 * 0.5 * 0.5 * 9.81);
  // Off centre: the compound body turns the reference's way (negative yaw: pushed on its +y
  // side); the cylinder, deflected by the pointer's edge, follows the reference.
  const T37Result& turn_ref = Find(runs, "compound", true, "virtual-coupling@1ms");
  ASSERT_LT(turn_ref.yaw, -0.5) << "the reference did not turn the compound body";
  const T37Verdict turn = Judge(Find(runs, "compound", true, ld), turn_ref);
  ASSERT_TRUE(turn.same_turn.has_value());
  EXPECT_TRUE(*turn.same_turn);
  for (const char* shape : {"cylinder", "mesh"}) {
    const T37Verdict follow =
        Judge(Find(runs, shape, true, ld), Find(runs, shape, true, "virtual-coupling@1ms"));
    ASSERT_TRUE(follow.follows_ref.has_value()) << shape;
    EXPECT_TRUE(*follow.follows_ref) << shape << ": impulse off by " << *follow.force_vs_ref
                                     << ", position by " << *follow.pose_error << " m";
  }
}

}  // namespace
}  // namespace mrh::experiments::internal
