// SPDX-License-Identifier: Apache-2.0
// The drivers' scene-editing helpers: one replacement, the named element's attribute, and errors
// that name the scene and what to keep in it.
#include "experiments/experiment_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "mrh/core/error.h"

namespace mrh::experiments::internal {
namespace {

using ::testing::HasSubstr;
using ::testing::StrEq;
using ::testing::ThrowsMessage;

constexpr char kWhy[] = "the test driver needs it";

TEST(ReplaceOnceTest, ReplacesOnlyTheFirstOccurrence) {
  EXPECT_EQ(
      ReplaceOnce(R"(<a mass="1"/><b mass="1"/>)", R"(mass="1")", R"(mass="2")", "s.xml", kWhy),
      R"(<a mass="2"/><b mass="1"/>)");
}

TEST(ReplaceOnceTest, MissingTextIsAnErrorNamingTheFileAndTheText) {
  EXPECT_THAT(
      [] {
        ReplaceOnce("<a/>", R"(mass="60")", "", "scenes/s.xml", kWhy);
      },
      ThrowsMessage<RuntimeError>(
          StrEq(R"(scenes/s.xml: 'mass="60"' not found; the test driver needs it)")));
}

TEST(ReplaceAttributeTest, ReplacesTheNamedElementsAttributeInAnyAttributeOrder) {
  const std::string xml = R"(<mesh name="a" vertex="0 0 0"/>
<mesh vertex="1 2
              3 4" name="prism"/>)";
  EXPECT_EQ(ReplaceAttribute(xml, "mesh", "prism", "vertex", "5 6", "s.xml", kWhy),
            R"(<mesh name="a" vertex="0 0 0"/>
<mesh vertex="5 6" name="prism"/>)");
}

TEST(ReplaceAttributeTest, SkipsCommentsOtherElementsAndLookalikeAttributes) {
  const std::string xml = R"(<!-- <mesh name="prism" vertex="x"/> -->
<meshes name="prism" vertex="y"/><geom name="prism" vertex="z"/>
<mesh file_name="prism" name="prism" my_vertex="w" vertex="v"/>)";
  EXPECT_EQ(ReplaceAttribute(xml, "mesh", "prism", "vertex", "new", "s.xml", kWhy),
            R"(<!-- <mesh name="prism" vertex="x"/> -->
<meshes name="prism" vertex="y"/><geom name="prism" vertex="z"/>
<mesh file_name="prism" name="prism" my_vertex="w" vertex="new"/>)");
}

TEST(ReplaceAttributeTest, MissingAttributeIsAnErrorNamingFileElementAndAttribute) {
  EXPECT_THAT(
      [] {
        ReplaceAttribute(R"(<mesh name="prism" file="prism.stl"/>)", "mesh", "prism", "vertex",
                         "0 0 0", "scenes/s.xml", kWhy);
      },
      ThrowsMessage<RuntimeError>(StrEq(R"(scenes/s.xml: <mesh name="prism"> has no )"
                                        R"(vertex="..." attribute; the test driver needs it)")));
}

TEST(ReplaceAttributeTest, MissingElementIsAnErrorNamingFileAndElement) {
  EXPECT_THAT(
      [] {
        ReplaceAttribute(R"(<!-- <mesh name="prism" vertex="0"/> --><mesh name="cube"/>)", "mesh",
                         "prism", "vertex", "0 0 0", "scenes/s.xml", kWhy);
      },
      ThrowsMessage<RuntimeError>(
          StrEq(R"(scenes/s.xml: no <mesh name="prism"> element; the test driver needs it)")));
}

TEST(ReadTextTest, MissingFileIsAnErrorNamingIt) {
  EXPECT_THAT(
      [] {
        ReadText("/no/such/dir/scene.xml");
      },
      ThrowsMessage<RuntimeError>(HasSubstr("cannot read /no/such/dir/scene.xml")));
}

}  // namespace
}  // namespace mrh::experiments::internal
