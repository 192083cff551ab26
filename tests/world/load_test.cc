// SPDX-License-Identifier: Apache-2.0
// Tests of scene loading: MuJoCo errors as one line with file and line, the pointer body checks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "mrh/core/error.h"
#include "mrh/world/world.h"
#include "world_test_util.h"

namespace mrh::world {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::ThrowsMessage;

using testing::kNoPointer;

// A free box and a mocap pointer sphere placed inside it, in zero gravity.
constexpr char kPointerInBox[] = R"(
<mujoco>
  <option gravity="0 0 0"/>
  <worldbody>
    <body name="box" pos="0 0 0">
      <freejoint/>
      <geom name="box" type="box" size="0.1 0.1 0.1" mass="1"/>
    </body>
    <body name="pointer" mocap="true" pos="0.02 0 0">
      <geom name="tip" type="sphere" size="0.02"/>
    </body>
  </worldbody>
</mujoco>)";

TEST(LoadStringTest, BadElementReportsOriginAndLineOnOneLine) {
  const std::string xml = "<mujoco>\n<worldbody>\n<foo/>\n</worldbody>\n</mujoco>\n";
  EXPECT_THAT(
      [&] {
        World::LoadString(xml, kNoPointer, "bad.xml");
      },
      ThrowsMessage<SceneError>(AllOf(HasSubstr("bad.xml: "), HasSubstr("line 3"),
                                      HasSubstr("'foo'"), Not(HasSubstr("\n")))));
}

TEST(LoadStringTest, MalformedXmlReportsLine) {
  const std::string xml = "<mujoco>\n<worldbody>\n<geom type=\"box\" size=\"1 1 1\"\n</worldbody>";
  EXPECT_THAT(
      [&] {
        World::LoadString(xml, kNoPointer, "broken.xml");
      },
      ThrowsMessage<SceneError>(
          AllOf(HasSubstr("broken.xml: XML parse error"), HasSubstr("Line number=3"))));
}

TEST(LoadStringTest, EmptyTextIsASceneError) {
  EXPECT_THAT(
      [] {
        World::LoadString("", kNoPointer, "empty.xml");
      },
      ThrowsMessage<SceneError>(HasSubstr("empty.xml: the scene text is empty")));
}

TEST(LoadFileTest, MissingFileSaysNotFound) {
  EXPECT_THAT(
      [] {
        World::LoadFile("/nonexistent/scene.xml");
      },
      ThrowsMessage<SceneError>(
          HasSubstr("/nonexistent/scene.xml: scene file not found (working directory")));
}

TEST(LoadFileTest, ReadsSceneFromDiskAndNamesItInErrors) {
  const auto path = std::filesystem::temp_directory_path() / "mrh_world_load_test.xml";
  {
    std::ofstream(path) << "<mujoco>\n<worldbody>\n<body name=\"b\">\n<geom type=\"sphere\" "
                           "size=\"0.1\"/>\n</body>\n</worldbody>\n</mujoco>\n";
  }
  const World world = World::LoadFile(path, kNoPointer);
  EXPECT_EQ(world.FindBody("b"), 1);
  EXPECT_THAT(
      [&] {
        World::LoadFile(path);
      },
      ThrowsMessage<SceneError>(HasSubstr(path.string() + ": pointer body 'pointer'")));
  std::filesystem::remove(path);
}

TEST(PointerBodyTest, MissingPointerNamesBodyAndFix) {
  const std::string xml =
      "<mujoco><worldbody><body name=\"b\"><geom size=\"0.1\"/></body>"
      "</worldbody></mujoco>";
  EXPECT_THAT(
      [&] {
        World::LoadString(xml, {}, "scene.xml");
      },
      ThrowsMessage<SceneError>(
          HasSubstr("scene.xml: pointer body 'pointer' not found; add <body "
                    "name=\"pointer\" mocap=\"true\"> as a child of <worldbody>, or set "
                    "pointer.body")));
}

TEST(PointerBodyTest, PointerThatIsNotMocapIsRejected) {
  const std::string xml =
      "<mujoco><worldbody><body name=\"pointer\"><freejoint/>"
      "<geom size=\"0.1\"/></body></worldbody></mujoco>";
  EXPECT_THAT(
      [&] {
        World::LoadString(xml, {}, "scene.xml");
      },
      ThrowsMessage<SceneError>(
          HasSubstr("scene.xml: pointer body 'pointer' is not a mocap body; add")));
}

TEST(PointerBodyTest, EmptyPointerNameMeansNoPointer) {
  const World world = World::LoadString(kPointerInBox, kNoPointer);
  EXPECT_EQ(world.pointer_body(), -1);
}

TEST(PointerBodyTest, PointerIsFoundByName) {
  const World world = World::LoadString(kPointerInBox);
  EXPECT_EQ(world.pointer_body(), world.FindBody("pointer"));
  EXPECT_TRUE(world.body(world.pointer_body()).is_mocap);
  EXPECT_TRUE(world.body(world.pointer_body()).is_static);  // no degrees of freedom
}

TEST(PointerBodyTest, PointerGeomsDoNotCollideInsideMuJoCo) {
  World world = World::LoadString(kPointerInBox);
  world.Step();
  EXPECT_EQ(world.num_contacts(), 0);
  EXPECT_FALSE(world.geom(world.body(world.pointer_body()).geoms[0]).collides);
  // Control: the same scene without a pointer does collide, so the check above can fail.
  World plain = World::LoadString(kPointerInBox, kNoPointer);
  plain.Step();
  EXPECT_GT(plain.num_contacts(), 0);
}

TEST(PointerBodyTest, ExplicitContactPairWithPointerIsRejected) {
  std::string xml = kPointerInBox;
  xml.replace(xml.find("</mujoco>"), 9,
              "<contact><pair geom1=\"box\" geom2=\"tip\"/></contact></mujoco>");
  EXPECT_THAT(
      [&] {
        World::LoadString(xml, {}, "pair.xml");
      },
      ThrowsMessage<SceneError>(
          HasSubstr("pair.xml: <contact><pair> #0 involves a geom of pointer body "
                    "'pointer'; remove the pair")));
}

TEST(LoadStringTest, HeightFieldIsRejectedWithFix) {
  const std::string xml =
      "<mujoco><asset><hfield name=\"terrain\" nrow=\"3\" ncol=\"3\" size=\"1 1 0.1 0.1\"/>"
      "</asset><worldbody><geom name=\"ground\" type=\"hfield\" hfield=\"terrain\"/>"
      "</worldbody></mujoco>";
  EXPECT_THAT(
      [&] {
        World::LoadString(xml, kNoPointer, "terrain.xml");
      },
      ThrowsMessage<SceneError>(
          HasSubstr("terrain.xml: geom 'ground' of body 'world' is a height field")));
}

}  // namespace
}  // namespace mrh::world
