// SPDX-License-Identifier: Apache-2.0
// Several pointers in the outputs: ticks.csv's `pointer` column and summary.json's
// per-pointer blocks appear with two or more pointers only.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mrh/report/report.h"
#include "report/report_test_util.h"

namespace mrh::report {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using testing::ReadLines;
using testing::ReadText;
using testing::TempDir;

constexpr const char* kOnePointerHeader =
    "t,px,py,pz,qw,qx,qy,qz,fx,fy,fz,tx,ty,tz,contacts,safety";

std::vector<std::string> WriteTicks(const TempDir& dir, std::vector<std::string> names) {
  CsvRecorder recorder(dir.path(), std::move(names));
  for (int pointer = 0; pointer < 2; ++pointer) {
    ir::TickRecord tick;
    tick.t = 0.5;
    tick.pointer = pointer;
    tick.displayed_W.f = Vec3(1.0 + pointer, 0.0, 0.0);
    tick.contacts = 1;
    recorder.OnTick(tick);
  }
  recorder.Close();
  return ReadLines(dir.path() / "ticks.csv");
}

TEST(PointerColumnTest, SeveralPointersNameEachRowsPointer) {
  const TempDir dir;
  const std::vector<std::string> lines = WriteTicks(dir, {"thumb", "index"});
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], std::string(kOnePointerHeader) + ",pointer");
  EXPECT_EQ(lines[1], "0.5,0,0,0,1,0,0,0,1,0,0,0,0,0,1,0,thumb");
  EXPECT_EQ(lines[2], "0.5,0,0,0,1,0,0,0,2,0,0,0,0,0,1,0,index");
}

TEST(PointerColumnTest, OnePointerKeepsTheFormat) {
  for (const std::vector<std::string>& names :
       {std::vector<std::string>{}, std::vector<std::string>{"pointer"}}) {
    const TempDir dir;
    const std::vector<std::string> lines = WriteTicks(dir, names);
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_EQ(lines[0], kOnePointerHeader);
    EXPECT_EQ(lines[1], "0.5,0,0,0,1,0,0,0,1,0,0,0,0,0,1,0");
  }
}

TEST(PointerColumnTest, SummaryHasPerPointerBlocksOnlyWithSeveral) {
  engine::RunStats stats;
  EXPECT_FALSE(nlohmann::json::parse(SummaryJson(stats, "s.json", "x.xml")).contains("pointers"));
  engine::PointerRunStats thumb;
  thumb.body = "thumb";
  thumb.max_force = 3.5;
  thumb.mean_force = 1.25;
  thumb.force_clamped = 4;
  thumb.device.wrenches_sent = 9;
  engine::PointerRunStats index;
  index.body = "index";
  stats.pointers = {thumb, index};
  const nlohmann::json summary = nlohmann::json::parse(SummaryJson(stats, "s.json", "x.xml"));
  ASSERT_EQ(summary["pointers"].size(), 2u);
  EXPECT_EQ(summary["pointers"][0]["body"], "thumb");
  EXPECT_EQ(summary["pointers"][0]["max_force"], 3.5);
  EXPECT_EQ(summary["pointers"][0]["mean_force"], 1.25);
  EXPECT_EQ(summary["pointers"][0]["faults"]["force_clamped"], 4);
  EXPECT_EQ(summary["pointers"][0]["device"]["wrenches_sent"], 9);
  EXPECT_EQ(summary["pointers"][1]["body"], "index");
}

// report.png with several pointers: each pointer's rows (every 2::i) drawn in its own colour;
// gnuplot must accept the script and draw the PNG.
TEST(PointerColumnTest, ReportDrawsEachPointerInItsOwnColour) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "no gnuplot";
  const TempDir dir;
  {
    CsvRecorder recorder(dir.path(), {"thumb", "index"});
    for (int k = 0; k < 10; ++k) {
      for (int pointer = 0; pointer < 2; ++pointer) {
        ir::TickRecord tick;
        tick.tick = k;
        tick.t = 0.001 * k;
        tick.pointer = pointer;
        tick.displayed_W.f = Vec3(0.0, pointer == 0 ? 1.0 : -1.0, 0.0);
        recorder.OnTick(tick);
      }
    }
    recorder.Close();
  }
  std::string why;
  ASSERT_TRUE(PlotReport(dir.path(), "two fingers", &why,
                         ReportOptions{.six_dof = false, .pointers = {"thumb", "index"}}))
      << why;
  const std::string script = ReadText(dir.path() / "report.gp");
  EXPECT_THAT(script, HasSubstr("every 2::0 using 1:(fnorm($9, $10, $11)) with lines lt 1 "
                                "title '|f| thumb'"));
  EXPECT_THAT(script, HasSubstr("every 2::1 using 1:(fnorm($9, $10, $11)) with lines lt 2 "
                                "title '|f| index'"));
  EXPECT_THAT(script, HasSubstr("title 'index z'"));
  // One pointer keeps the one-pointer panels.
  ASSERT_TRUE(PlotReport(dir.path(), "one", &why, ReportOptions{.six_dof = false})) << why;
  EXPECT_THAT(ReadText(dir.path() / "report.gp"), Not(HasSubstr("every 2::")));
}

}  // namespace
}  // namespace mrh::report
