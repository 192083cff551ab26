// SPDX-License-Identifier: Apache-2.0
// The `pointers` form of a session: values, the one-element form, element errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "mrh/session/session.h"
#include "session/session_test_util.h"

namespace mrh::session {
namespace {

using testing::Parse;
using testing::ThrowsInvalid;

constexpr const char* kFixed = R"({"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0]})";

std::string WithPointers(const std::string& pointers, const std::string& extra = "") {
  return R"({"scene": "scene.xml", "method": "single-rate", "pointers": )" + pointers +
         (extra.empty() ? std::string() : ", " + extra) + "}";
}

std::string Element(const std::string& body, const std::string& more = "") {
  return R"({"body": ")" + body + R"(", "device": )" + kFixed +
         (more.empty() ? std::string() : ", " + more) + "}";
}

TEST(PointersSessionTest, ReadsEveryPointerWithItsDeviceAndOverrides) {
  const Session s = Parse(WithPointers("[" + Element("f0", R"("radius": 0.01)") + ", " +
                                           R"({"body": "f1", "rendering": {"stiffness": 500},
              "device": {"type": "fixed", "pose": [0.1, 0, 0, 1, 0, 0, 0]}}])",
                                       R"("rendering": {"stiffness": 800, "damping": 2})"));
  ASSERT_EQ(s.engine.pointers.size(), 2u);
  ASSERT_EQ(s.pointer_devices.size(), 2u);
  EXPECT_EQ(s.engine.num_pointers(), 2);
  EXPECT_EQ(s.engine.pointer.body, "f0");
  EXPECT_EQ(s.engine.pointers[0].pointer.radius, 0.01);
  EXPECT_EQ(s.engine.pointers[1].pointer.body, "f1");
  EXPECT_EQ(s.engine.pointers[0].rendering.stiffness, 800.0);
  EXPECT_EQ(s.engine.pointers[1].rendering.stiffness, 500.0);
  EXPECT_EQ(s.engine.pointers[1].rendering.damping, 2.0);  // not overridden: the session's
  EXPECT_EQ(s.pointer_devices[1].pose.p.x(), 0.1);
  EXPECT_EQ(s.device.pose.p.x(), 0.0);
}

// One element means exactly the single `pointer` + `device` form.
TEST(PointersSessionTest, OneElementIsTheSinglePointerForm) {
  const Session list = Parse(WithPointers("[" + Element("pointer", R"("radius": 0.02)") + "]"));
  const Session single = Parse(
      R"({"scene": "scene.xml", "method": "single-rate", "pointer": {"radius": 0.02},
          "device": )" +
      std::string(kFixed) + "}");
  EXPECT_TRUE(list.engine.pointers.empty());
  EXPECT_TRUE(list.pointer_devices.empty());
  EXPECT_EQ(list.engine.num_pointers(), 1);
  EXPECT_EQ(list.engine.pointer.body, single.engine.pointer.body);
  EXPECT_EQ(list.engine.pointer.radius, single.engine.pointer.radius);
  EXPECT_EQ(list.device.type, single.device.type);
  EXPECT_EQ(list.engine.rendering.stiffness, single.engine.rendering.stiffness);
}

TEST(PointersSessionTest, ADeviceErrorNamesTheElement) {
  EXPECT_THAT(
      [] {
        Parse(WithPointers("[" + Element("f0") +
                           R"(, {"body": "f1", "device": {"type": "glove"}}])"));
      },
      ThrowsInvalid("pointers[1].device.type"));
}

TEST(PointersSessionTest, ARenderingErrorNamesTheElement) {
  EXPECT_THAT(
      [] {
        Parse(WithPointers("[" + Element("f0") + ", " +
                           Element("f1", R"("rendering": {"stiffness": -5})") + "]"));
      },
      ThrowsInvalid("pointers[1].rendering.stiffness"));
}

TEST(PointersSessionTest, BodiesMustBeDistinct) {
  EXPECT_THAT(
      [] {
        Parse(WithPointers("[" + Element("f0") + ", " + Element("f0") + "]"));
      },
      ThrowsInvalid("pointers[1].body: \"f0\" is also pointers[0].body"));
}

TEST(PointersSessionTest, ABodyIsRequired) {
  EXPECT_THAT(
      [] {
        Parse(WithPointers("[" + Element("f0") + R"(, {"device": {"type": "fixed"}}])"));
      },
      ThrowsInvalid("pointers[1].body: missing"));
}

TEST(PointersSessionTest, UnknownElementKeyIsNamed) {
  EXPECT_THAT(
      [] {
        Parse(WithPointers("[" + Element("f0", R"("colour": 1)") + "]"));
      },
      ThrowsInvalid("pointers[0]"));
}

TEST(PointersSessionTest, TheTwoFormsDoNotMix) {
  EXPECT_THAT(
      [] {
        Parse(WithPointers("[" + Element("f0") + "]", R"("device": {"type": "fixed"})"));
      },
      ThrowsInvalid("pointers: given together with \"device\""));
  EXPECT_THAT(
      [] {
        Parse(WithPointers("[]"));
      },
      ThrowsInvalid("pointers: an empty array"));
  EXPECT_THAT(
      [] {
        Parse(WithPointers(Element("f0")));
      },
      ThrowsInvalid("pointers:"));
}

TEST(PointersSessionTest, AStiffnessAboveTheElementsDeviceLimitNamesTheElement) {
  EXPECT_THAT(
      [] {
        Parse(
            WithPointers("[" + Element("f0") + R"(, {"body": "f1", "rendering": {"stiffness": 5000},
              "device": {"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0],
                         "limits": {"max_stiffness": 1000}}}])"));
      },
      ThrowsInvalid("pointers[1]: rendering.stiffness = 5000 N/m exceeds"));
}

}  // namespace
}  // namespace mrh::session
