// SPDX-License-Identifier: Apache-2.0
// The T3.4 driver renders an N-gon prism with N contact points (timings are not checked; contact
// counts, convergence and the analytic sliding force are), and scenes/t3_4.json runs its setup.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "experiment_test_util.h"
#include "experiments/experiment_util.h"
#include "experiments/experiments_impl.h"
#include "mrh/core/error.h"
#include "mrh/session/session.h"

namespace mrh::experiments {
namespace {

TEST(T34ExperimentTest, PrismBaseGivesOneContactPerSideAndAFrictionRowEach) {
  const std::filesystem::path out = testing::TempDir("mrh_experiments_test_t3_4_");
  std::filesystem::remove_all(out);
  internal::T34Options options;
  options.sides = {5, 100, 1000};
  options.duration = 0.06;  // three physics steps; the first is not counted
  ASSERT_EQ(internal::RunT34(out, /*quiet=*/true, options), 0);
  std::ifstream in(out / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  ASSERT_EQ(s["runs"].size(), 6u);
  testing::ExpectAllChecksPass(s);
  for (const nlohmann::json& run : s["runs"]) {
    const int sides = run["sides"].get<int>();
    EXPECT_EQ(run["contacts"].get<int>(), sides);
    EXPECT_EQ(run["rows"].get<int>(), run["friction"].get<bool>() ? 2 * sides : sides);
    EXPECT_GT(run["p50_us"].get<double>(), 0.0);
    EXPECT_EQ(run["unconverged_ticks"].get<int>(), 0) << sides;
    EXPECT_LT(run["force_error_N"].get<double>(), 9000.0 * 1e-8) << sides;  // k_t × 1e-8 m
  }
  EXPECT_TRUE(std::filesystem::exists(out / "t3_4.csv"));
  std::filesystem::remove_all(out);
}

// The session runs the driver's setup through the engine on the scene's 12-gon: the base is
// δ = 1 mm deep and slides at v = 0.1 m/s, so f = k_t δ ẑ − min(k_t v t, μ k_t δ) x̂ (sticking
// for μδ/v = 5 ms, then kinetic on the cone boundary), on all 12 base vertices with a friction
// row each once it has moved (at t = 0 there is no tangential offset, hence no friction row,
// eq. 3.10 needs a slip direction). Every base vertex is on the floor, so any tilt of the proxy
// would push half of them into it: the proxy only translates and the torque stays 0.
TEST(T34SessionTest, SessionSlidesTheTwelveGonWithTheDriversForce) {
  const session::Session session = session::LoadSession(internal::ScenesDir() / "t3_4.json");
  const internal::ProxyRun run = internal::RunProxySession(session, {}, "", /*quiet=*/true);
  const settings::RenderingSettings& r = session.engine.rendering;
  constexpr double kDepth = 1e-3, kSpeed = 0.1;                 // m, m/s (t3_4_trajectory.csv)
  constexpr int kSides = 12;                                    // scenes/t3_4.xml
  constexpr double kPointAccuracy = 1e-8;                       // m, as the driver's force check
  const double force_tolerance = kPointAccuracy * r.stiffness;  // N
  const double torque_tolerance = kPointAccuracy * r.rot_stiffness;  // N·m
  ASSERT_EQ(run.ticks.size(), 2000u);
  for (const internal::ProxyTick& tick : run.ticks) {
    const double f_t = std::min(r.stiffness * kSpeed * tick.t, r.friction * r.stiffness * kDepth);
    const Vec3 expected(-f_t, 0.0, r.stiffness * kDepth);
    EXPECT_LT((tick.w_W.f - expected).norm(), force_tolerance) << "t = " << tick.t;
    EXPECT_LT(tick.w_W.tau.norm(), torque_tolerance) << "t = " << tick.t;
    EXPECT_EQ(tick.constrained_p_PV.size(), static_cast<std::size_t>(kSides)) << tick.t;
    EXPECT_EQ(tick.diagnostics.rows, tick.t > 0.0 ? 2 * kSides : kSides) << "t = " << tick.t;
  }
}

// Sets an environment variable for the scope of the test and restores it after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = ::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }

  ~ScopedEnv() {
    if (old_) {
      ::setenv(name_, old_->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }

  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(T34ExperimentTest, SceneWithoutThePrismVertexListIsAnErrorNamingTheFile) {
  const std::filesystem::path scenes = testing::TempDir("mrh_t3_4_scenes_");
  std::filesystem::create_directories(scenes);
  std::ofstream(scenes / "t3_4.xml") << R"(<mujoco><asset><mesh name="prism" file="p.stl"/>
</asset></mujoco>)";
  const ScopedEnv env("MRH_SCENES_DIR", scenes.string());
  internal::T34Options options;
  options.sides = {5};
  options.duration = 0.04;
  EXPECT_THAT(
      [&] {
        internal::RunT34(scenes / "out", /*quiet=*/true, options);
      },
      ::testing::ThrowsMessage<RuntimeError>(::testing::HasSubstr(
          (scenes / "t3_4.xml").string() + R"(: <mesh name="prism"> has no vertex="..." )")));
  std::filesystem::remove_all(scenes);
}

}  // namespace
}  // namespace mrh::experiments
