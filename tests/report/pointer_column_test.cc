// SPDX-License-Identifier: Apache-2.0
// Several pointers in the outputs (issue 35): ticks.csv's `pointer` column and summary.json's
// per-pointer blocks appear with two or more pointers only.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mrh/report/report.h"
#include "report/report_test_util.h"

namespace mrh::report {
namespace {

using testing::ReadLines;
using testing::TempDir;

constexpr const char* kOnePointerHeader =
    "t,px,py,pz,qw,qx,qy,qz,fx,fy,fz,tx,ty,tz,contacts,safety";

std::vector<std::string> WriteTicks(const TempDir& dir, std::vector<std::string> names) {
  CsvRecorder recorder(dir.path(), std::move(names));
  for (int pointer = 0; pointer < 2; ++pointer) {
    engine::TickRecord tick;
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

}  // namespace
}  // namespace mrh::report
