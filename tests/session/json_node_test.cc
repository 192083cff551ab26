// SPDX-License-Identifier: Apache-2.0
// Tests of the key and type checks: unknown keys anywhere, wrong types, dotted paths.
#include "session/json_node.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "session/session_test_util.h"

namespace mrh::session {
namespace {

using ::testing::HasSubstr;
using testing::Minimal;
using ::testing::Not;
using testing::Parse;
using testing::ThrowsInvalid;
using testing::ThrowsInvalidExactly;
using ::testing::ThrowsMessage;
using testing::WithDevice;

TEST(SessionKeysTest, UnknownTopLevelKeyListsTheAllowedKeysAndTheClosestOne) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("phyiscs_dt": 0.01)"));
      },
      ThrowsInvalidExactly(
          "session.json: phyiscs_dt: unknown key; expected one of: scene, mode, keyframe, "
          "gravity, device, psychophysics, materials, pointers, method, physics_dt, haptic_dt, "
          "duration, "
          "realtime_priority, "
          "pointer, rendering, safety (did you mean \"physics_dt\"?)"));
}

TEST(SessionKeysTest, UnknownNestedKeyIsNamedByItsFullDottedPath) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": {"stifness": 1000})"));
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

TEST(SessionKeysTest, UnknownKeyUnlikeAnyAllowedKeyGetsNoSuggestion) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("pointer": {"colour": "red"})"));
      },
      ThrowsInvalidExactly("session.json: pointer.colour: unknown key; expected one of: "
                           "body, radius"));
}

TEST(SessionKeysTest, UnknownSafetyKeyIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("safety": {"ramp_tim": 1})"));
      },
      ThrowsInvalid("session.json: safety.ramp_tim: unknown key; expected one of: ramp, "
                    "ramp_time, watchdog_timeout, watchdog_fade"));
}

TEST(SessionKeysTest, UnknownDeviceKeyListsEveryDeviceKey) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0], "gain": 1})"));
      },
      ThrowsInvalid("session.json: device.gain: unknown key; expected one of: type, model, "
                    "limits, calibration, pose, keyframes, trajectory, hand, replay, library, "
                    "id, name, bind, timeout, fade"));
}

TEST(SessionKeysTest, UnknownKeyTwoLevelsDownIsNamedByItsFullPath) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(
            R"({"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0], "calibration": {"offset": 1}})"));
      },
      ThrowsInvalid("session.json: device.calibration.offset: unknown key; expected one of: "
                    "position, orientation, scale"));
}

TEST(SessionKeysTest, UnknownHandAndLimitKeysAreErrors) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "hand", "keyframes": [[0, 0, 0, 0, 1, 0, 0, 0]],
                             "hand": {"weight": 1}})"));
      },
      ThrowsInvalid("session.json: device.hand.weight: unknown key; expected one of: mass,"));
  EXPECT_THAT(
      [] {
        Parse(WithDevice(
            R"({"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0], "limits": {"force": 1}})"));
      },
      ThrowsInvalid("session.json: device.limits.force: unknown key; expected one of: max_force, "
                    "max_torque, max_stiffness"));
}

TEST(SessionKeysTest, NumberGivenAsStringNamesKeyExpectedTypeAndValue) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("physics_dt": "fast")"));
      },
      ThrowsInvalidExactly(
          "session.json: physics_dt: found a string (\"fast\"); expected a number in s"));
}

TEST(SessionKeysTest, FlagGivenAsNumberIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("realtime_priority": 1)"));
      },
      ThrowsInvalidExactly("session.json: realtime_priority: found a number (1); "
                           "expected true or false"));
}

TEST(SessionKeysTest, StringGivenAsNumberIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("method": 5)"));
      },
      ThrowsInvalidExactly("session.json: method: found a number (5); expected a string"));
}

TEST(SessionKeysTest, NullIsDescribedAsNull) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("keyframe": null)"));
      },
      ThrowsInvalidExactly("session.json: keyframe: found null; expected a string"));
}

TEST(SessionKeysTest, BooleanIsDescribedWithItsValue) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": {"stiffness": true})"));
      },
      ThrowsInvalidExactly("session.json: rendering.stiffness: found a boolean (true); "
                           "expected a number in N/m"));
}

TEST(SessionKeysTest, BlockGivenAsNumberListsItsKeys) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": 5)"));
      },
      ThrowsInvalidExactly(
          "session.json: rendering: found a number (5); expected an object with keys: "
          "stiffness, damping, neighbor_distance, neighbor_margin, curved_segments, rot_stiffness, "
          "rot_damping, rotation_weight_scale, friction, torque_model, proxy_solver, "
          "max_iterations, "
          "solver_tolerance, proxy_reaction, perturbation, perturbation_force, local_model, "
          "coupling_stiffness, "
          "coupling_damping, coupling_rot_stiffness, coupling_rot_damping, tool_mass, "
          "rotation_weight, tool_inertia"));
}

TEST(SessionKeysTest, WrongArrayElementIsNamedByIndex) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("gravity": [0, "x", 0])"));
      },
      ThrowsInvalidExactly("session.json: gravity[1]: found a string (\"x\"); expected a number"));
}

TEST(SessionKeysTest, LongStringValueIsShortenedInTheMessage) {
  const std::string value(60, 'a');
  EXPECT_THAT(
      [&] {
        Parse(Minimal(R"("duration": ")" + value + R"(")"));
      },
      ThrowsInvalid("found a string (\"" + std::string(40, 'a') + "...\")"));
}

TEST(SessionKeysTest, ErrorInTheFileDoesNotMentionOverrides) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("mode": 1)"));
      },
      ThrowsMessage<InvalidArgument>(Not(HasSubstr("--set"))));
}

TEST(SessionKeysTest, DescribeNamesEveryJsonType) {
  using nlohmann::json;
  EXPECT_EQ(internal::Describe(json()), "null");
  EXPECT_EQ(internal::Describe(json(false)), "a boolean (false)");
  EXPECT_EQ(internal::Describe(json(2.5)), "a number (2.5)");
  EXPECT_EQ(internal::Describe(json(-3)), "a number (-3)");
  EXPECT_EQ(internal::Describe(json("x")), "a string (\"x\")");
  EXPECT_EQ(internal::Describe(json::array()), "an array of 0 elements");
  EXPECT_EQ(internal::Describe(json::object()), "an object");
}

}  // namespace
}  // namespace mrh::session
