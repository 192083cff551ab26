// SPDX-License-Identifier: Apache-2.0
// The shared range checks: numbers printed faithfully, one message shape.
#include "mrh/core/validate.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "mrh/core/error.h"

namespace mrh {
namespace {

using ::testing::ThrowsMessage;

TEST(FormatNumberTest, PrintsDenormalsHugeAndNonFiniteValuesFaithfully) {
  EXPECT_EQ(FormatNumber(5e-324), "5e-324");
  EXPECT_EQ(FormatNumber(1e-320), "1e-320");
  EXPECT_EQ(FormatNumber(2.2250738585072014e-308), "2.2250738585072014e-308");
  EXPECT_EQ(FormatNumber(1e308), "1e+308");
  EXPECT_EQ(FormatNumber(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(FormatNumber(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(FormatNumber(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(FormatNumber(-std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(FormatNumber(0.1), "0.1");
  EXPECT_EQ(FormatNumber(4294967.296), "4294967.296");
}

TEST(RequireTest, MessagesNameKeyValueUnitAndRange) {
  EXPECT_THAT(
      [] {
        RequirePositive(0.0, "haptic_dt", "s");
      },
      ThrowsMessage<InvalidArgument>("haptic_dt = 0 s; expected a finite value > 0"));
  EXPECT_THAT(
      [] {
        RequireNonNegative(1e308, "safety.watchdog_timeout", "s", 3600.0);
      },
      ThrowsMessage<InvalidArgument>(
          "safety.watchdog_timeout = 1e+308 s; expected a finite value >= 0 and <= 3600 s"));
  EXPECT_THAT(
      [] {
        RequireInRange(5e-324, 1e-3, 1e3, "rendering.perturbation_force", "N");
      },
      ThrowsMessage<InvalidArgument>("rendering.perturbation_force = 5e-324 N; expected a "
                                     "finite value in [0.001, 1000] N"));
  EXPECT_NO_THROW(RequireInRange(1e-3, 1e-3, 1e3, "k", ""));
  EXPECT_NO_THROW(RequirePositive(1e300, "k", ""));
}

TEST(PoseProblemTest, HugeQuaternionIsNotReportedAsZero) {
  const Problem p = PoseProblem(Vec3::Zero(), Quat(1e200, 0, 0, 0));
  EXPECT_EQ(p.what, "quaternion (qw, qx, qy, qz) = (1e+200, 0, 0, 0)");
  EXPECT_TRUE(PoseProblem(Vec3(0, 0, 0), Quat(0, 0, 0, 0)));
  EXPECT_TRUE(PoseProblem(Vec3(1e308, 0, 0), Quat::Identity()));
  EXPECT_FALSE(PoseProblem(Vec3(1, 2, 3), Quat(0.99999, 0, 0, 0)));
}

TEST(KeyframeTimeProblemTest, TimesCloserThanAMicrosecondAreRefused) {
  EXPECT_TRUE(KeyframeTimeProblem(5e-324, 0.0));
  EXPECT_FALSE(KeyframeTimeProblem(1e-3, 0.0));
  EXPECT_FALSE(KeyframeTimeProblem(0.0, std::numeric_limits<double>::quiet_NaN()));
  EXPECT_TRUE(KeyframeTimeProblem(std::numeric_limits<double>::infinity(), 0.0));
}

TEST(ErrorTest, NulAndLineBreaksCannotCutOrSplitTheMessage) {
  const InvalidArgument e(std::string("a\0b\nc", 5));
  EXPECT_STREQ(e.what(), "a\\x00b c");
}

}  // namespace
}  // namespace mrh
