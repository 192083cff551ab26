// SPDX-License-Identifier: Apache-2.0
// Tests of LoadSession / ParseSession: values, defaults, paths, file errors and engine validation.
#include "mrh/session/session.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "session/session_test_util.h"

namespace mrh::session {
namespace {

namespace fs = std::filesystem;
using testing::FixturesDir;
using testing::Minimal;
using testing::Parse;
using testing::ThrowsInvalid;
using testing::ThrowsInvalidExactly;

TEST(SessionTest, LoadsTheTopLevelEngineSettings) {
  const Session s = LoadSession(FixturesDir() / "fixed.json");
  EXPECT_EQ(s.engine.method, "impulse");
  EXPECT_EQ(s.engine.mode, settings::Mode::kLockstep);
  EXPECT_DOUBLE_EQ(s.engine.physics_dt, 0.05);
  EXPECT_DOUBLE_EQ(s.engine.haptic_dt, 0.001);
  EXPECT_DOUBLE_EQ(s.engine.duration, 2.0);
  EXPECT_FALSE(s.engine.realtime_priority);
  EXPECT_EQ(s.keyframe, "start");
  ASSERT_TRUE(s.gravity.has_value());
  EXPECT_EQ(*s.gravity, Vec3::Zero());
}

TEST(SessionTest, LoadsThePointerRenderingAndSafetyBlocks) {
  const Session s = LoadSession(FixturesDir() / "fixed.json");
  EXPECT_EQ(s.engine.pointer.body, "pointer");
  EXPECT_DOUBLE_EQ(s.engine.pointer.radius, 0.02);
  EXPECT_DOUBLE_EQ(s.engine.rendering.stiffness, 1500.0);
  EXPECT_DOUBLE_EQ(s.engine.rendering.damping, 2.5);
  EXPECT_DOUBLE_EQ(s.engine.rendering.neighbor_distance, 0.04);
  EXPECT_DOUBLE_EQ(s.engine.rendering.neighbor_margin, 0.06);
  EXPECT_FALSE(s.engine.safety.ramp);
  EXPECT_DOUBLE_EQ(s.engine.safety.ramp_time, 0.3);
  EXPECT_DOUBLE_EQ(s.engine.safety.watchdog_timeout, 0.2);
  EXPECT_DOUBLE_EQ(s.engine.safety.watchdog_fade, 0.05);
}

// The default method is the proposed one, not the impulse baseline.
TEST(SessionTest, ASessionThatNamesNoMethodGetsTheProposedMethod) {
  EXPECT_EQ(Parse(Minimal()).engine.method, "local-dynamics");
  EXPECT_EQ(Parse(Minimal(R"("method": "impulse")")).engine.method, "impulse");
}

TEST(SessionTest, OmittedKeysKeepTheSettingsDefaults) {
  const Session s = Parse(Minimal());
  const settings::EngineSettings defaults;
  EXPECT_EQ(s.engine.mode, defaults.mode);
  EXPECT_EQ(s.engine.physics_dt, defaults.physics_dt);
  EXPECT_EQ(s.engine.haptic_dt, defaults.haptic_dt);
  EXPECT_EQ(s.engine.duration, defaults.duration);
  EXPECT_EQ(s.engine.realtime_priority, defaults.realtime_priority);
  EXPECT_EQ(s.engine.pointer.body, defaults.pointer.body);
  EXPECT_EQ(s.engine.pointer.radius, defaults.pointer.radius);
  EXPECT_EQ(s.engine.rendering.stiffness, defaults.rendering.stiffness);
  EXPECT_EQ(s.engine.rendering.neighbor_margin, defaults.rendering.neighbor_margin);
  EXPECT_EQ(s.engine.safety.ramp, defaults.safety.ramp);
  EXPECT_EQ(s.engine.safety.ramp_time, defaults.safety.ramp_time);
  EXPECT_TRUE(s.keyframe.empty());
  EXPECT_FALSE(s.gravity.has_value());
}

TEST(SessionTest, IntegerLiteralsAreAcceptedAsNumbers) {
  const Session s = Parse(Minimal(R"("rendering": {"stiffness": 2000}, "duration": 3)"));
  EXPECT_DOUBLE_EQ(s.engine.rendering.stiffness, 2000.0);
  EXPECT_DOUBLE_EQ(s.engine.duration, 3.0);
}

TEST(SessionTest, RealtimeModeIsParsed) {
  EXPECT_EQ(Parse(Minimal(R"("mode": "realtime")")).engine.mode, settings::Mode::kRealtime);
}

TEST(SessionTest, UnknownModeIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("mode": "fast")"));
      },
      ThrowsInvalidExactly("session.json: mode: unknown mode \"fast\"; expected "
                           "\"lockstep\" or \"realtime\""));
}

TEST(SessionTest, GravityNeedsThreeNumbers) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("gravity": [0, -9.81])"));
      },
      ThrowsInvalidExactly("session.json: gravity: found an array of 2 elements; expected "
                           "an array of 3 numbers [gx, gy, gz] (m/s^2)"));
}

TEST(SessionTest, GravityIsParsedInOrder) {
  const Session s = Parse(Minimal(R"("gravity": [1, 2, -9.81])"));
  ASSERT_TRUE(s.gravity.has_value());
  EXPECT_EQ(*s.gravity, Vec3(1, 2, -9.81));
}

TEST(SessionTest, ParsedTextIsNamedByItsOrigin) {
  EXPECT_EQ(Parse(Minimal()).file, fs::path("session.json"));
  EXPECT_EQ(ParseSession(Minimal(), FixturesDir()).file, fs::path("<string>"));
}

TEST(SessionTest, LoadedFileIsNamedAsGiven) {
  const fs::path file = FixturesDir() / "fixed.json";
  EXPECT_EQ(LoadSession(file).file, file);
}

TEST(SessionTest, ScenePathIsResolvedAgainstTheSessionFolder) {
  const Session s = LoadSession(FixturesDir() / "nested" / "session.json");
  EXPECT_EQ(s.scene, (FixturesDir() / "scene.xml").lexically_normal());
  EXPECT_TRUE(s.scene.is_absolute());
}

TEST(SessionTest, AbsoluteScenePathIsKept) {
  const fs::path scene = (FixturesDir() / "scene.xml").lexically_normal();
  const std::string text = R"({"scene": ")" + scene.string() +
                           R"(", "device": {"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0]}})";
  EXPECT_EQ(ParseSession(text, "/").scene, scene);
}

TEST(SessionTest, MissingSceneIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(R"({"device": {"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0]}})");
      },
      ThrowsInvalidExactly(
          "session.json: scene: missing; expected the MJCF scene's path (string)"));
}

TEST(SessionTest, NonexistentSceneFileIsAnErrorNamingKeyAndPath) {
  const std::string missing = (FixturesDir() / "no_such_scene.xml").lexically_normal().string();
  EXPECT_THAT(
      [] {
        Parse(R"({"scene": "no_such_scene.xml", "device": {"type": "fixed"}})");
      },
      ThrowsInvalid("session.json: scene: file " + missing +
                    " does not exist; expected the MJCF scene file as a path relative to the "
                    "session file's folder " +
                    FixturesDir().lexically_normal().string()));
}

TEST(SessionTest, SceneThatIsAFolderIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(R"({"scene": "nested", "device": {"type": "fixed"}})");
      },
      ThrowsInvalid(
          "session.json: scene: " + (FixturesDir() / "nested").lexically_normal().string() +
          " is a directory; expected the MJCF scene file"));
}

TEST(SessionTest, EmptyScenePathIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(R"({"scene": "", "device": {"type": "fixed"}})");
      },
      ThrowsInvalid("session.json: scene: the path is empty; expected the MJCF scene"));
}

TEST(SessionTest, MissingDeviceIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(R"({"scene": "scene.xml"})");
      },
      ThrowsInvalid("session.json: device: missing; expected an object"));
}

TEST(SessionTest, DocumentThatIsNotAnObjectIsAnError) {
  EXPECT_THAT(
      [] {
        Parse("[1]");
      },
      ThrowsInvalidExactly("session.json: (top level): found an array of 1 element; "
                           "expected a JSON object {...} of session keys"));
}

TEST(SessionTest, EngineValidationErrorIsPrefixedWithTheFile) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("physics_dt": -1)"));
      },
      ThrowsInvalidExactly("session.json: physics_dt = -1 s; expected a finite value > 0 and "
                           "<= 1 s"));
}

TEST(SessionTest, PhysicsPeriodMustBeAWholeNumberOfTicks) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("physics_dt": 0.0025, "haptic_dt": 0.001)"));
      },
      ThrowsInvalid("session.json: physics_dt = 0.0025 s is not a whole multiple"));
}

TEST(SessionTest, NegativeRenderingGainIsAnErrorNamingTheKey) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": {"damping": -1})"));
      },
      ThrowsInvalid("session.json: rendering.damping = -1 N*s/m; expected"));
}

TEST(SessionTest, NegativeSafetyTimeIsAnErrorNamingTheKey) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("safety": {"ramp_time": -0.5})"));
      },
      ThrowsInvalid("session.json: safety.ramp_time = -0.5 s; expected"));
}

TEST(SessionTest, EmptyPointerBodyIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("pointer": {"body": ""})"));
      },
      ThrowsInvalid("session.json: pointer.body is empty"));
}

TEST(SessionTest, MissingSessionFileIsAnError) {
  EXPECT_THAT(
      [] {
        LoadSession("no_such_session.json");
      },
      ThrowsInvalidExactly("no_such_session.json: session file does not exist or is not "
                           "a regular file; expected the path of a session JSON file"));
}

TEST(SessionTest, SessionFileThatIsAFolderIsAnError) {
  EXPECT_THAT(
      [] {
        LoadSession(FixturesDir() / "nested");
      },
      ThrowsInvalid("nested: session file does not exist or is not a regular file"));
}

TEST(SessionTest, SyntaxErrorInAFileNamesFileLineAndColumn) {
  const fs::path file = FixturesDir() / "syntax_error.json";
  EXPECT_THAT(
      [&] {
        LoadSession(file);
      },
      ThrowsInvalid(file.string() + ":4:13: syntax error while parsing object"));
}

TEST(SessionTest, EveryRepositorySessionFileLoads) {
  const fs::path scenes = fs::path(MRH_SOURCE_DIR) / "scenes";
  if (!fs::is_directory(scenes)) GTEST_SKIP() << "no scenes/ folder";
  int loaded = 0;
  for (const auto& entry : fs::directory_iterator(scenes)) {
    if (entry.path().extension() != ".json") continue;
    try {
      LoadSession(entry.path());
    } catch (const Error& e) {
      ADD_FAILURE() << e.what();
    }
    ++loaded;
  }
  EXPECT_GT(loaded, 0);
}

TEST(SessionTest, ProxyAndLocalDynamicsKeysAreParsed) {
  const Session s = Parse(Minimal(
      R"("rendering": {"torque_model": "thesis", "rot_stiffness": 9000, "rot_damping": 3,
                       "rotation_weight": [1, 2, 3],
                       "friction": 0.5, "max_iterations": 20, "curved_segments": 24,
                       "perturbation": false, "perturbation_force": 0.25})"));
  EXPECT_EQ(s.engine.rendering.rot_stiffness, 9000.0);
  EXPECT_EQ(s.engine.rendering.rot_damping, 3.0);
  ASSERT_TRUE(s.engine.rendering.rotation_weight.has_value());
  EXPECT_EQ(*s.engine.rendering.rotation_weight, Vec3(1, 2, 3));
  EXPECT_EQ(s.engine.rendering.friction, 0.5);
  EXPECT_EQ(s.engine.rendering.max_iterations, 20);
  EXPECT_EQ(s.engine.rendering.curved_segments, 24);
  EXPECT_FALSE(s.engine.rendering.perturbation);
  EXPECT_EQ(s.engine.rendering.perturbation_force, 0.25);
}

TEST(SessionTest, FractionalIterationCountIsAnErrorNamingTheKey) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": {"max_iterations": 20.5})"));
      },
      ThrowsInvalid("rendering.max_iterations: found"));
}

TEST(SessionTest, RotationWeightNeedsThreePositiveNumbers) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": {"rotation_weight": [1, 2]})"));
      },
      ThrowsInvalid("rendering.rotation_weight"));
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": {"rotation_weight": [1, 0, 2]})"));
      },
      ThrowsInvalid("rendering.rotation_weight = [1, 0, 2] m^2; expected three finite"));
}

TEST(SessionTest, TooFewCurvedSegmentsIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": {"curved_segments": 4})"));
      },
      ThrowsInvalid("rendering.curved_segments = 4; expected a whole number in [6, 1024]"));
}

}  // namespace
}  // namespace mrh::session
