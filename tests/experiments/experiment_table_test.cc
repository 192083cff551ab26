// SPDX-License-Identifier: Apache-2.0
// The drivers' shared writer: a table's CSV, Markdown and JSON, and a checks list whose empty
// form is a failure.
#include "experiments/experiment_table.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "mrh/core/error.h"

namespace mrh::experiments::internal {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

TEST(TableTest, WritesCsvMarkdownAndJson) {
  Table t({"name", "x_m", "n"});
  t.Add({"a", "0.500", "3"});
  t.AddFormatted("{},{:.3f},{}", "b", 0.25, 4);
  t.Add({"", "1e-3", "x"});
  EXPECT_EQ(t.Csv(), "name,x_m,n\na,0.500,3\nb,0.250,4\n,1e-3,x\n");
  EXPECT_EQ(t.Markdown(),
            "| name | x_m | n |\n|---|---|---|\n| a | 0.500 | 3 |\n| b | 0.250 | 4 |\n"
            "| | 1e-3 | x |\n");
  const nlohmann::json j = t.Json();
  ASSERT_EQ(j.size(), 3u);
  EXPECT_EQ(j[0]["name"], "a");
  EXPECT_EQ(j[0]["x_m"], 0.5);
  EXPECT_EQ(j[1]["n"], 4.0);
  EXPECT_EQ(j[2]["x_m"], 1e-3);
  EXPECT_EQ(j[2]["n"], "x");  // not a number: kept as text
}

TEST(TableTest, RowOfTheWrongWidthIsAnErrorNamingTheColumns) {
  Table t({"a", "b"});
  EXPECT_THAT(
      [&] {
        t.Add({"1"});
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("table row has 1 cells; expected 2")));
  EXPECT_THAT(
      [&] {
        t.AddFormatted("{},{},{}", 1, 2, 3);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("columns a,b")));
}

TEST(ChecksTest, EmptyListFails) {
  EXPECT_FALSE(Checks{}.ok());
  EXPECT_EQ(Checks{}.Json(), nlohmann::json::object());
}

TEST(ChecksTest, OkOnlyIfEveryCheckPasses) {
  Checks checks;
  checks.Add("b_passes", true);
  EXPECT_TRUE(checks.ok());
  checks.Add("a_fails", false, 2.0, 1.0);
  EXPECT_FALSE(checks.ok());
  EXPECT_EQ(checks.Json(), (nlohmann::json{{"a_fails", false}, {"b_passes", true}}));
  EXPECT_EQ(checks.Markdown(),
            "| check | value | bound | result |\n|---|---|---|---|\n"
            "| b_passes | | | pass |\n| a_fails | 2 | 1 | FAIL |\n");
  std::ostringstream printed;
  checks.Print(printed);
  EXPECT_EQ(printed.str(), "check a_fails: FAIL\ncheck b_passes: pass\n");
}

TEST(ChecksTest, AddJsonTakesEveryNamedResult) {
  Checks checks;
  checks.AddJson({{"x", true}, {"y", false}});
  EXPECT_FALSE(checks.ok());
  EXPECT_EQ(checks.Json(), (nlohmann::json{{"x", true}, {"y", false}}));
}

}  // namespace
}  // namespace mrh::experiments::internal
