// SPDX-License-Identifier: Apache-2.0
// Tests of `--set dotted.key=value` overrides: values, creation of blocks, errors and provenance.
#include "session/overrides.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "session/session_test_util.h"

namespace mrh::session {
namespace {

using testing::FixturesDir;
using testing::Minimal;
using testing::Parse;
using testing::ThrowsInvalid;
using testing::ThrowsInvalidExactly;

TEST(OverridesTest, NumberReplacesTheFileValue) {
  const Session s = Parse(Minimal(R"("physics_dt": 0.05)"), {"physics_dt=0.01"});
  EXPECT_DOUBLE_EQ(s.engine.physics_dt, 0.01);
}

TEST(OverridesTest, MissingBlockIsCreated) {
  const Session s = Parse(Minimal(), {"rendering.stiffness=2500"});
  EXPECT_DOUBLE_EQ(s.engine.rendering.stiffness, 2500.0);
}

TEST(OverridesTest, OtherKeysOfTheBlockAreKept) {
  const Session s = Parse(Minimal(R"("rendering": {"damping": 3})"), {"rendering.stiffness=2500"});
  EXPECT_DOUBLE_EQ(s.engine.rendering.damping, 3.0);
}

TEST(OverridesTest, ValueThatIsNotJsonIsTakenAsAString) {
  const Session s = Parse(Minimal(), {"method=single-rate", "keyframe=start"});
  EXPECT_EQ(s.engine.method, "single-rate");
  EXPECT_EQ(s.keyframe, "start");
}

TEST(OverridesTest, QuotedValueStaysAStringEvenIfItLooksLikeANumber) {
  EXPECT_EQ(Parse(Minimal(), {R"(keyframe="123")"}).keyframe, "123");
}

TEST(OverridesTest, EmptyValueIsAnEmptyString) {
  EXPECT_EQ(Parse(Minimal(R"("keyframe": "start")"), {"keyframe="}).keyframe, "");
}

TEST(OverridesTest, ValueMayContainAnEqualsSign) {
  EXPECT_EQ(Parse(Minimal(), {"keyframe=a=b"}).keyframe, "a=b");
}

TEST(OverridesTest, BooleanAndArrayValuesAreParsedAsJson) {
  const Session s =
      Parse(Minimal(), {"realtime_priority=false", "device.pose=[0, 0, 0.5, 1, 0, 0, 0]"});
  EXPECT_FALSE(s.engine.realtime_priority);
  EXPECT_DOUBLE_EQ(s.device.pose.p.z(), 0.5);
}

TEST(OverridesTest, LaterOverrideOfTheSameKeyWins) {
  const Session s = Parse(Minimal(), {"duration=1", "duration=4"});
  EXPECT_DOUBLE_EQ(s.engine.duration, 4.0);
}

TEST(OverridesTest, OverridesApplyToLoadedFiles) {
  const Session s = LoadSession(FixturesDir() / "fixed.json", {"safety.ramp=true"});
  EXPECT_TRUE(s.engine.safety.ramp);
}

TEST(OverridesTest, OverriddenPathIsResolvedAgainstTheSessionFolder) {
  const Session s =
      LoadSession(FixturesDir() / "nested" / "session.json", {"device.trajectory=../approach.csv"});
  EXPECT_EQ(s.device.trajectory, (FixturesDir() / "approach.csv").lexically_normal());
}

TEST(OverridesTest, MissingEqualsSignIsAnErrorNamingTheOverride) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(), {"physics_dt"});
      },
      ThrowsInvalidExactly("session.json: --set physics_dt: missing '='; expected "
                           "KEY=VALUE, e.g. --set rendering.stiffness=2000"));
}

TEST(OverridesTest, EmptyKeyIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(), {"=5"});
      },
      ThrowsInvalidExactly("session.json: --set =5: empty key in \"\"; expected a dotted "
                           "key such as rendering.stiffness"));
}

TEST(OverridesTest, EmptyPathSegmentIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(), {"rendering..stiffness=5"});
      },
      ThrowsInvalid("session.json: --set rendering..stiffness=5: empty key in "
                    "\"rendering..stiffness\""));
}

TEST(OverridesTest, PathThroughANumberIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": {"stiffness": 1500})"), {"rendering.stiffness.x=1"});
      },
      ThrowsInvalidExactly("session.json: --set rendering.stiffness.x=1: rendering.stiffness is "
                           "a number (1500), not an object; expected a key path through objects "
                           "only (set rendering.stiffness as a whole: --set "
                           "rendering.stiffness=...)"));
}

TEST(OverridesTest, PathThroughAnArrayIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(), {"device.pose.x=1"});
      },
      ThrowsInvalid("session.json: --set device.pose.x=1: device.pose is an array of 7 "
                    "elements, not an object"));
}

TEST(OverridesTest, UnknownKeyFromAnOverrideSaysItCameFromSet) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(), {"rendering.stifness=5"});
      },
      ThrowsInvalidExactly(
          "session.json: rendering.stifness: unknown key (from --set "
          "rendering.stifness=5); expected one of: stiffness, damping, neighbor_distance, "
          "neighbor_margin, curved_segments, rot_stiffness, rot_damping, rotation_weight_scale, "
          "friction, torque_model, proxy_solver, max_iterations, solver_tolerance, proxy_reaction, "
          "perturbation, "
          "perturbation_force, local_model, coupling_stiffness, coupling_damping, "
          "coupling_rot_stiffness, coupling_rot_damping, tool_mass, "
          "rotation_weight, tool_inertia (did you mean \"stiffness\"?)"));
}

TEST(OverridesTest, UnknownBlockCreatedByAnOverrideSaysItCameFromSet) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(), {"render.stiffness=5"});
      },
      ThrowsInvalid("session.json: render: unknown key (from --set render.stiffness=5); "
                    "expected one of:"));
}

TEST(OverridesTest, WrongTypeFromAnOverrideSaysItCameFromSet) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(), {"physics_dt=fast"});
      },
      ThrowsInvalidExactly("session.json: physics_dt: found a string (\"fast\") (from "
                           "--set physics_dt=fast); expected a number in s"));
}

TEST(OverridesTest, ErrorInsideAnOverriddenArraySaysItCameFromSet) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(), {"gravity=[0, 0, true]"});
      },
      ThrowsInvalid("session.json: gravity[2]: found a boolean (true) (from --set "
                    "gravity=[0, 0, true])"));
}

TEST(OverridesTest, ErrorInAnotherKeyDoesNotBlameTheOverride) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": {"stifness": 1})"), {"rendering.damping=1"});
      },
      ThrowsInvalidExactly(
          "session.json: rendering.stifness: unknown key; expected one of: stiffness, "
          "damping, neighbor_distance, neighbor_margin, curved_segments, rot_stiffness, "
          "rot_damping, rotation_weight_scale, "
          "friction, torque_model, proxy_solver, max_iterations, solver_tolerance, proxy_reaction, "
          "perturbation, "
          "perturbation_force, local_model, coupling_stiffness, coupling_damping, "
          "coupling_rot_stiffness, coupling_rot_damping, tool_mass, "
          "rotation_weight, tool_inertia (did you mean \"stiffness\"?)"));
}

}  // namespace
}  // namespace mrh::session
