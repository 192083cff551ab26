// SPDX-License-Identifier: Apache-2.0
// The `materials` block: parsing, defaults, and the errors that name file, key and value.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mrh/session/session.h"
#include "session/session_test_util.h"

namespace mrh::session::testing {
namespace {

TEST(MaterialsSessionTest, ReadsEveryFieldOfAMaterial) {
  const Session s = Parse(Minimal(R"("materials": {"alu": {"stiffness": 3000, "damping": 2,
      "friction": 0.3, "vibration": {"amplitude": 20, "decay": 60, "frequency": 250}}})"));
  const settings::MaterialSettings& m = s.engine.rendering.materials.at("alu");
  EXPECT_EQ(m.stiffness, 3000.0);
  EXPECT_EQ(m.damping, 2.0);
  EXPECT_EQ(m.friction, 0.3);
  ASSERT_TRUE(m.vibration.has_value());
  EXPECT_EQ(m.vibration->amplitude, 20.0);
  EXPECT_EQ(m.vibration->decay, 60.0);
  EXPECT_EQ(m.vibration->frequency, 250.0);
}

TEST(MaterialsSessionTest, UnsetFieldsStayUnsetForTheRenderingDefaults) {
  const Session s = Parse(Minimal(R"("materials": {"wood": {"stiffness": 1500}})"));
  const settings::MaterialSettings& m = s.engine.rendering.materials.at("wood");
  EXPECT_FALSE(m.damping.has_value());
  EXPECT_FALSE(m.friction.has_value());
  EXPECT_FALSE(m.vibration.has_value());
}

TEST(MaterialsSessionTest, NoMaterialsKeyMeansNoMaterials) {
  EXPECT_TRUE(Parse(Minimal()).engine.rendering.materials.empty());
}

TEST(MaterialsSessionTest, NegativeStiffnessNamesFileKeyAndValue) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("materials": {"alu": {"stiffness": -5}})"));
      },
      ThrowsInvalid("session.json: materials.alu.stiffness = -5 N/m; expected"));
}

TEST(MaterialsSessionTest, NegativeFrictionNamesFileKeyAndValue) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("materials": {"alu": {"friction": -0.1}})"));
      },
      ThrowsInvalid("session.json: materials.alu.friction = -0.1"));
}

TEST(MaterialsSessionTest, ZeroDecayIsRejected) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(
            R"("materials": {"alu": {"vibration": {"amplitude": 1, "decay": 0, "frequency": 9}}})"));
      },
      ThrowsInvalid("session.json: materials.alu.vibration.decay = 0 1/s"));
}

TEST(MaterialsSessionTest, AVibrationNeedsAllThreeKeys) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("materials": {"alu": {"vibration": {"amplitude": 1}}})"));
      },
      ThrowsInvalid("materials.alu.vibration.decay: missing"));
}

TEST(MaterialsSessionTest, AnUnknownKeyInAMaterialIsNamed) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("materials": {"alu": {"stifness": 5}})"));
      },
      ThrowsInvalid("materials.alu.stifness: unknown key"));
}

TEST(MaterialsSessionTest, AMaterialMustBeAnObject) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("materials": {"alu": 5})"));
      },
      ThrowsInvalid("materials.alu"));
}

TEST(MaterialsSessionTest, OverridesReachAMaterial) {
  const Session s = Parse(Minimal(R"("materials": {"alu": {"stiffness": 3000}})"),
                          {"materials.alu.stiffness=2500"});
  EXPECT_EQ(s.engine.rendering.materials.at("alu").stiffness, 2500.0);
}

}  // namespace
}  // namespace mrh::session::testing
