// SPDX-License-Identifier: Apache-2.0
// Tests of PlotReport: a PNG from a tiny ticks.csv, and the reasons it gives when it cannot plot.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>

#include "mrh/device/safety.h"
#include "mrh/report/report.h"
#include "report/report_test_util.h"

namespace mrh::report {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using testing::ReadText;
using ::testing::StartsWith;
using testing::TempDir;

bool HaveGnuplot() {
  return std::system("command -v gnuplot > /dev/null 2>&1") == 0;
}

// A half second of a pointer pressing into a surface at 1 kHz.
void WriteTicks(const std::filesystem::path& dir) {
  CsvRecorder recorder(dir);
  for (int i = 0; i < 500; ++i) {
    ir::TickRecord tick;
    tick.t = i * 0.001;
    tick.X_WP.p = Vec3(0.0, 0.0, 0.1 - tick.t * 0.01);
    tick.displayed_W.f = Vec3(0.1, 0.0, 2.0 * std::sin(tick.t * 10.0));
    tick.displayed_W.tau = Vec3(0.0, 0.01, 0.0);
    recorder.OnTick(tick);
  }
  recorder.Close();
}

// Sets PATH for the scope of one test and restores it afterwards.
class ScopedPath {
 public:
  explicit ScopedPath(const std::string& value) {
    if (const char* old = std::getenv("PATH")) old_ = old;
    ::setenv("PATH", value.c_str(), 1);
  }

  ~ScopedPath() {
    if (old_) {
      ::setenv("PATH", old_->c_str(), 1);
    } else {
      ::unsetenv("PATH");
    }
  }

  ScopedPath(const ScopedPath&) = delete;
  ScopedPath& operator=(const ScopedPath&) = delete;

 private:
  std::optional<std::string> old_;
};

TEST(PlotReportTest, TinyTicksCsvGivesPngAndRerunnableScript) {
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const TempDir dir;
  WriteTicks(dir.path());
  std::string why = "unset";
  ASSERT_TRUE(PlotReport(dir.path(), "impulse: cube push", &why)) << why;
  EXPECT_EQ(why, "");
  const std::string png = ReadText(dir.path() / "report.png");
  EXPECT_THAT(png, StartsWith("\x89PNG\r\n\x1a\n"));
  EXPECT_GT(png.size(), 1000u);
  EXPECT_THAT(ReadText(dir.path() / "report.gp"), HasSubstr("'ticks.csv'"));
}

TEST(PlotReportTest, TitleWithQuotesAndBackslashStillPlots) {
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const TempDir dir;
  WriteTicks(dir.path());
  std::string why;
  EXPECT_TRUE(PlotReport(dir.path(), R"(it's a "test" \n {x})", &why)) << why;
}

TEST(PlotReportTest, MissingGnuplotSaysWhatToInstall) {
  const TempDir dir;
  WriteTicks(dir.path());
  const ScopedPath path((dir.path() / "no-such-bin").string());
  std::string why;
  EXPECT_FALSE(PlotReport(dir.path(), "t", &why));
  EXPECT_EQ(why, "gnuplot not found; install gnuplot-nox");
}

TEST(PlotReportTest, MissingTicksCsvFailsWithGnuplotMessage) {
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const TempDir dir;
  std::string why;
  EXPECT_FALSE(PlotReport(dir.path(), "t", &why));
  EXPECT_THAT(why, HasSubstr("gnuplot failed"));
  EXPECT_THAT(why, HasSubstr("ticks.csv"));
  EXPECT_EQ(why.find('\n'), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "report.png"));
}

// The lines of `text` that start with `prefix`.
std::vector<std::string> LinesStartingWith(const std::string& text, const std::string& prefix) {
  std::vector<std::string> out;
  std::stringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(prefix, 0) == 0) out.push_back(line);
  }
  return out;
}

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

// Plots and returns report.gp; fails the test if gnuplot rejects the script.
std::string PlotAndReadScript(const TempDir& dir, const ReportOptions& options) {
  std::string why;
  EXPECT_TRUE(PlotReport(dir.path(), "run", &why, options)) << why;
  return ReadText(dir.path() / "report.gp");
}

// bodies.csv by hand: `n` bodies named b0.. at 20 ms steps to t_end; body k moves k cm along x
// per second, so the most moved is the last.
void WriteBodies(const std::filesystem::path& dir, int n, double t_end) {
  std::ofstream file(dir / "bodies.csv");
  file << "t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,cx,cy,cz\n";
  for (int step = 0; step * 0.02 <= t_end + 1e-9; ++step) {
    const double t = step * 0.02;
    for (int k = 0; k < n; ++k) {
      const double x = 0.01 * k * t;
      file << t << ",b" << k << "," << x << ",0,0.05,1,0,0,0,0,0,0,0,0,0," << x << ",0,0.05\n";
    }
  }
}

TEST(PlotReportTest, ThreeDofRunDrawsNoTorqueOrOrientationPanel) {
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const TempDir dir;
  WriteTicks(dir.path());
  const std::string script = PlotAndReadScript(dir, ReportOptions{.six_dof = false});
  EXPECT_THAT(script, HasSubstr("set multiplot layout 2,1"));
  EXPECT_THAT(script, HasSubstr("'force (N)'"));
  EXPECT_THAT(script, HasSubstr("'pointer position (m)'"));
  EXPECT_THAT(script, Not(HasSubstr("torque")));
  EXPECT_THAT(script, Not(HasSubstr("rotation")));
  EXPECT_THAT(script, Not(HasSubstr("bodies.csv' every")));  // no bodies: no objects panel
}

TEST(PlotReportTest, SixDofRunAddsTorqueAndOrientationPanels) {
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const TempDir dir;
  WriteTicks(dir.path());
  const std::string script = PlotAndReadScript(dir, ReportOptions{.six_dof = true});
  EXPECT_THAT(script, HasSubstr("set multiplot layout 4,1"));
  EXPECT_THAT(script, HasSubstr("'torque (N m)'"));
  EXPECT_THAT(script, HasSubstr("'pointer rotation (deg)'"));
  EXPECT_EQ(LinesStartingWith(script, "plot ").size(), 4u);
}

TEST(PlotReportTest, ObjectsPanelHasOneLegendEntryPerBody) {
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const TempDir dir;
  WriteTicks(dir.path());
  WriteBodies(dir.path(), 3, 0.4);
  const std::string script = PlotAndReadScript(dir, ReportOptions{.six_dof = false});
  EXPECT_THAT(script, HasSubstr("set multiplot layout 3,1"));
  for (const char* name : {"b0", "b1", "b2"}) {
    EXPECT_EQ(Count(script, fmt::format("title '{}'", name)), 1u) << name;
  }
  // Rows come three per step: body k is every third row from row k.
  EXPECT_THAT(script, HasSubstr("'bodies.csv' every 3::0 "));
  EXPECT_THAT(script, HasSubstr("every 3::2 "));
  EXPECT_THAT(script, Not(HasSubstr("objects shown")));
}

TEST(PlotReportTest, ManyBodiesShowTouchedThenMostMovedAndSaySo) {
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const TempDir dir;
  WriteTicks(dir.path());
  WriteBodies(dir.path(), 5, 0.4);
  const std::string script = PlotAndReadScript(
      dir, ReportOptions{.six_dof = false, .touched_bodies = {"b1"}, .max_legend_bodies = 2});
  EXPECT_THAT(script, HasSubstr("2 of 5 objects shown"));
  EXPECT_THAT(script, HasSubstr("title 'b1'"));  // touched
  EXPECT_THAT(script, HasSubstr("title 'b4'"));  // moved most
  for (const char* name : {"b0", "b2", "b3"}) {
    EXPECT_THAT(script, Not(HasSubstr(fmt::format("title '{}'", name))));
  }
}

TEST(PlotReportTest, ClampedTicksAndContactLossesAreMarkedWithTheirCounts) {
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const TempDir dir;
  {
    CsvRecorder recorder(dir.path());
    for (int i = 0; i < 100; ++i) {
      ir::TickRecord tick;
      tick.t = i * 0.001;
      // In contact on ticks 10-29 and 50-59: two losses, at ticks 30 and 60.
      tick.contacts = (i >= 10 && i < 30) || (i >= 50 && i < 60) ? 1 : 0;
      tick.displayed_W.f = Vec3(0.0, 0.0, tick.contacts * 3.0);
      // Clamped on ticks 20, 21 and 22 (force) and 55 (torque); ramping alone is no clamp.
      if (i >= 20 && i <= 22) tick.safety_bits = device::kSafetyForceClamped;
      if (i == 55) tick.safety_bits = device::kSafetyTorqueClamped;
      if (i < 5) tick.safety_bits = device::kSafetyRamping;
      recorder.OnTick(tick);
    }
    recorder.Close();
  }
  const std::string script = PlotAndReadScript(dir, ReportOptions{.six_dof = false});
  EXPECT_THAT(script, HasSubstr("title 'clamped (4 ticks)'"));
  EXPECT_THAT(script, HasSubstr("title 'contact lost (2)'"));
}

TEST(PlotReportTest, RunWithoutClampingOrContactLossHasNoMarks) {
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const TempDir dir;
  WriteTicks(dir.path());  // no safety bits, no contacts
  const std::string script = PlotAndReadScript(dir, ReportOptions{});
  EXPECT_THAT(script, Not(HasSubstr("clamped")));
  EXPECT_THAT(script, Not(HasSubstr("contact lost")));
}

// Bodies recorded past the last tick: every panel still spans the same interval, the later one.
TEST(PlotReportTest, AllPanelsShareOneTimeAxis) {
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const TempDir dir;
  WriteTicks(dir.path());           // t = 0 .. 0.499
  WriteBodies(dir.path(), 2, 0.6);  // t = 0 .. 0.6
  const std::string script = PlotAndReadScript(dir, ReportOptions{});
  const std::vector<std::string> ranges = LinesStartingWith(script, "set xrange");
  ASSERT_EQ(ranges.size(), 1u);
  EXPECT_EQ(ranges[0], "set xrange [0:0.6]");
  EXPECT_LT(script.find("set xrange"), script.find("set multiplot"));
  // Only the bottom panel is labelled with time.
  EXPECT_EQ(Count(script, "set xlabel"), 1u);
  EXPECT_GT(script.find("set xlabel"), script.rfind("set ylabel"));
}

}  // namespace
}  // namespace mrh::report
