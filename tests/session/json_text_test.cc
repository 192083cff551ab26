// SPDX-License-Identifier: Apache-2.0
// Tests of JSON text errors: file:line:column positions, number overflow, duplicate keys.
#include "session/json_text.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "session/session_test_util.h"

namespace mrh::session {
namespace {

using internal::PositionOf;
using testing::Minimal;
using testing::Parse;
using testing::ThrowsInvalid;
using testing::ThrowsInvalidExactly;

TEST(JsonTextTest, PositionCountsLinesAndColumnsFromOne) {
  const std::string text = "ab\ncd\n";
  EXPECT_EQ(PositionOf(text, 0).line, 1u);
  EXPECT_EQ(PositionOf(text, 0).column, 1u);
  EXPECT_EQ(PositionOf(text, 2).column, 3u);  // the first newline ends line 1
  EXPECT_EQ(PositionOf(text, 4).line, 2u);
  EXPECT_EQ(PositionOf(text, 4).column, 2u);
  EXPECT_EQ(PositionOf(text, 100).line, 3u);  // past the end: just after the last newline
  EXPECT_EQ(PositionOf(text, 100).column, 1u);
}

TEST(JsonTextTest, InvalidLiteralNamesLineAndColumnOfTheOffendingCharacter) {
  const std::string text = "{\n  \"scene\": \"scene.xml\",\n  \"physics_dt\": x\n}";
  EXPECT_THAT(
      [&] {
        Parse(text);
      },
      ThrowsInvalidExactly("session.json:3:17: syntax error while parsing value - "
                           "invalid literal; last read: '\"physics_dt\": x'"));
}

TEST(JsonTextTest, TrailingCommaIsASyntaxError) {
  EXPECT_THAT(
      [] {
        Parse(R"({"scene": "scene.xml",})");
      },
      ThrowsInvalidExactly("session.json:1:23: syntax error while parsing object key - "
                           "unexpected '}'; expected string literal"));
}

TEST(JsonTextTest, NewlineInsideAStringIsLocatedAtTheEndOfItsLine) {
  EXPECT_THAT(
      [] {
        Parse("{\"scene\": \"a\nb\"}");
      },
      ThrowsInvalid("session.json:1:13: syntax error while parsing value - invalid "
                    "string: control character U+000A (LF) must be escaped"));
}

TEST(JsonTextTest, EmptyTextIsASyntaxErrorAtTheStart) {
  EXPECT_THAT(
      [] {
        Parse("");
      },
      ThrowsInvalid("session.json:1:1: syntax error while parsing value - unexpected end "
                    "of input"));
}

TEST(JsonTextTest, NumberTooLargeForADoubleIsLocated) {
  EXPECT_THAT(
      [] {
        Parse("{\n  \"duration\": 1e400\n}");
      },
      ThrowsInvalidExactly("session.json:2:15: number overflow parsing '1e400'; expected "
                           "a number of magnitude below 1.8e308"));
}

TEST(JsonTextTest, DuplicateTopLevelKeyIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("duration": 1, "duration": 2)"));
      },
      ThrowsInvalidExactly("session.json: duration: duplicate key; expected each key at "
                           "most once in an object (JSON would keep only the last value)"));
}

TEST(JsonTextTest, DuplicateNestedKeyIsNamedByItsPath) {
  EXPECT_THAT(
      [] {
        Parse(Minimal(R"("rendering": {"damping": 1, "stiffness": 1, "damping": 2})"));
      },
      ThrowsInvalid("session.json: rendering.damping: duplicate key"));
}

TEST(JsonTextTest, DuplicateKeyInsideAnArrayIsNamedWithTheIndex) {
  EXPECT_THAT(
      [] {
        Parse(R"({"a": [1, {"b": 1}, {"c": 1, "c": 2}]})");
      },
      ThrowsInvalid("session.json: a[2].c: duplicate key"));
}

TEST(JsonTextTest, SameKeyInDifferentObjectsIsAllowed) {
  const Session s = Parse(R"({"scene": "scene.xml", "rendering": {"stiffness": 10},
      "device": {"type": "hand", "keyframes": [[0, 0, 0, 0, 1, 0, 0, 0]],
                 "hand": {"stiffness": 20}}})");
  EXPECT_DOUBLE_EQ(s.engine.rendering.stiffness, 10.0);
  EXPECT_DOUBLE_EQ(s.device.hand.stiffness, 20.0);
}

}  // namespace
}  // namespace mrh::session
