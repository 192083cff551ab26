// SPDX-License-Identifier: Apache-2.0
// Tests of recording: a tick file the replay device plays back pose for pose.
#include "viewer/tick_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "mrh/core/error.h"
#include "mrh/device/simulated.h"

namespace mrh::viewer::internal {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// Shortest round-trip formatting makes the file lossless; interpolation at a knot is exact up to
// a few roundings.
constexpr double kTol = 1e-12;
constexpr double kDt = 1e-3;  // s

std::filesystem::path TestPath() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return std::filesystem::path(::testing::TempDir()) /
         (std::string("mrh_") + info->name() + "_" + std::to_string(::getpid())) / "ticks.csv";
}

TickSample Sample(double t, const Vec3& p, double angle) {
  TickSample s;
  s.t = t;
  s.X_WP = Pose{p, Quat(Eigen::AngleAxisd(angle, Vec3::UnitY()))};
  s.displayed_W.f = Vec3(1.0, 2.0, 3.0);
  s.contacts = 1;
  return s;
}

TEST(TickFileTest, ReplaysThePosesItRecordedFromTimeZero) {
  const std::filesystem::path path = TestPath();
  const TickSample a = Sample(12.0, Vec3(0.1, 0.2, 0.3), 0.1);
  const TickSample b = Sample(12.0 + kDt, Vec3(0.11, 0.2, 0.3), 0.2);
  {
    TickFile file(path);
    file.Write(a);
    file.Write(b);
    file.Close();
    EXPECT_EQ(file.rows(), 2);
  }
  const auto replay = device::MakeReplayDevice(path);
  const device::DeviceState first = replay->Read(0.0);
  const device::DeviceState second = replay->Read(kDt);
  EXPECT_TRUE(first.X_DT.p.isApprox(a.X_WP.p, kTol));
  EXPECT_TRUE(second.X_DT.p.isApprox(b.X_WP.p, kTol));
  EXPECT_NEAR(second.X_DT.q.angularDistance(b.X_WP.q), 0.0, kTol);
}

TEST(TickFileTest, WritesTheTicksCsvHeaderOfMrhRun) {
  const std::filesystem::path path = TestPath();
  {
    TickFile file(path);
    file.Write(Sample(3.0, Vec3::Zero(), 0.0));
    file.Close();
  }
  std::ifstream in(path);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_EQ(header, "t,px,py,pz,qw,qx,qy,qz,fx,fy,fz,tx,ty,tz,contacts");
  EXPECT_EQ(row, "0,0,0,0,1,0,0,0,1,2,3,0,0,0,1");
}

TEST(TickFileTest, AnUnwritablePathIsARuntimeErrorNamingIt) {
  EXPECT_THAT(
      [] {
        TickFile file("/dev/null/ticks.csv");
      },
      ThrowsMessage<RuntimeError>(HasSubstr("cannot open /dev/null/ticks.csv")));
}

}  // namespace
}  // namespace mrh::viewer::internal
