// SPDX-License-Identifier: Apache-2.0
// Tests of PlotReport: a PNG from a tiny ticks.csv, and the reasons it gives when it cannot plot.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <optional>

#include "mrh/report/report.h"
#include "report/report_test_util.h"

namespace mrh::report {
namespace {

using ::testing::HasSubstr;
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
    engine::TickRecord tick;
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

// A 3-DOF method's torque panel says so (its torque column is zero or rounding noise), and a
// run without body rows gets no objects panel (gnuplot refuses an empty data file).
TEST(PlotReportTest, ThreeDofTorquePanelIsLabelledAndNoObjectsPanelWithoutBodies) {
  if (!HaveGnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const TempDir dir;
  WriteTicks(dir.path());
  std::string why;
  ASSERT_TRUE(PlotReport(dir.path(), "impulse", &why, /*renders_torque=*/false)) << why;
  const std::string script = ReadText(dir.path() / "report.gp");
  EXPECT_THAT(script, HasSubstr("3-DOF method: no torque rendered"));
  EXPECT_THAT(script, ::testing::Not(HasSubstr("bodies.csv")));
  ASSERT_TRUE(PlotReport(dir.path(), "proxy-6dof", &why, /*renders_torque=*/true)) << why;
  EXPECT_THAT(ReadText(dir.path() / "report.gp"), ::testing::Not(HasSubstr("3-DOF")));
}


}  // namespace
}  // namespace mrh::report
