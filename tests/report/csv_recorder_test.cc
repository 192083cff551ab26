// SPDX-License-Identifier: Apache-2.0
// Tests of CsvRecorder: exact headers, rows read back, lossless numbers and I/O errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>

#include "mrh/core/error.h"
#include "mrh/device/safety.h"
#include "mrh/report/report.h"
#include "mrh/world/world.h"
#include "report/report_test_util.h"

namespace mrh::report {
namespace {

using ::testing::HasSubstr;
using testing::ReadLines;
using testing::SplitCsv;
using testing::TempDir;
using ::testing::ThrowsMessage;

double Parse(const std::string& text) {
  return std::strtod(text.c_str(), nullptr);
}

ir::TickRecord MakeTick(double t) {
  ir::TickRecord tick;
  tick.tick = 7;
  tick.t = t;
  tick.X_WP.p = Vec3(0.1, -0.2, 0.3);
  tick.X_WP.q = Quat(0.5, 0.5, -0.5, 0.5);
  tick.displayed_W.f = Vec3(1.5, -2.25, 3.0);
  tick.displayed_W.tau = Vec3(0.01, 0.02, -0.03);
  tick.rendered_W.f = Vec3(100.0, 200.0, 300.0);  // must not appear: the CSV holds the displayed
  tick.contacts = 2;
  tick.safety_bits = device::kSafetyForceClamped | device::kSafetyRamping;
  return tick;
}

TEST(CsvRecorderTest, WritesExactHeadersInAllThreeFiles) {
  const TempDir dir;
  CsvRecorder recorder(dir.path());
  recorder.Close();
  EXPECT_EQ(ReadLines(dir.path() / "ticks.csv"),
            std::vector<std::string>{"t,px,py,pz,qw,qx,qy,qz,fx,fy,fz,tx,ty,tz,contacts,safety"});
  EXPECT_EQ(ReadLines(dir.path() / "bodies.csv"),
            std::vector<std::string>{"t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,cx,cy,cz"});
  EXPECT_EQ(ReadLines(dir.path() / "steps.csv"),
            std::vector<std::string>{
                "t,step,compute_ms,sim_contacts,neighbors,point_contacts,solver_iterations,"
                "world_step_ms,ir_ms,model_ms,sync_ms"});
}

TEST(CsvRecorderTest, CreatesMissingNestedFolder) {
  const TempDir dir;
  const std::filesystem::path nested = dir.path() / "a" / "b";
  CsvRecorder recorder(nested);
  recorder.Close();
  EXPECT_TRUE(std::filesystem::exists(nested / "ticks.csv"));
}

TEST(CsvRecorderTest, TickRowHoldsPointerPoseAndDisplayedWrench) {
  const TempDir dir;
  CsvRecorder recorder(dir.path());
  recorder.OnTick(MakeTick(0.001));
  recorder.Close();
  const std::vector<std::string> lines = ReadLines(dir.path() / "ticks.csv");
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[1], "0.001,0.1,-0.2,0.3,0.5,0.5,-0.5,0.5,1.5,-2.25,3,0.01,0.02,-0.03,2,20");
}

TEST(CsvRecorderTest, StepRowHoldsEveryStepField) {
  const TempDir dir;
  world::World world = world::World::LoadString(
      "<mujoco><worldbody><geom type='plane' size='1 1 0.1'/></worldbody></mujoco>",
      world::LoadOptions{.pointer_body = ""});
  CsvRecorder recorder(dir.path());
  recorder.OnStep(physics::StepRecord{.step = 3,
                                      .t = 0.15,
                                      .compute_ms = 0.25,
                                      .sim_contacts = 4,
                                      .neighbors = 5,
                                      .point_contacts = 6,
                                      .solver_iterations = 7,
                                      .world_step_ms = 0.125,
                                      .ir_ms = 0.5,
                                      .model_ms = 2,
                                      .sync_ms = 0.0625},
                  world);
  recorder.Close();
  const std::vector<std::string> lines = ReadLines(dir.path() / "steps.csv");
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[1], "0.15,3,0.25,4,5,6,7,0.125,0.5,2,0.0625");
}

// Two free bodies (one named, one not) above a static floor; the floor and the world body
// must not appear in bodies.csv.
constexpr const char* kTwoBodies = R"(
<mujoco>
  <worldbody>
    <geom type="plane" size="1 1 0.1"/>
    <body name="box" pos="0 0 0.5" euler="0 0 30">
      <freejoint/>
      <geom type="box" size="0.1 0.1 0.1" pos="0.02 0 0" mass="1"/>
    </body>
    <body pos="0.5 0 0.5">
      <freejoint/>
      <geom type="sphere" size="0.05" mass="0.2"/>
    </body>
  </worldbody>
</mujoco>)";

TEST(CsvRecorderTest, BodyRowsMatchWorldStateForEachMovingBody) {
  const TempDir dir;
  world::World world = world::World::LoadString(kTwoBodies, world::LoadOptions{.pointer_body = ""});
  for (int i = 0; i < 5; ++i) world.Step();  // falling: non-zero velocity
  CsvRecorder recorder(dir.path());
  recorder.OnStep(physics::StepRecord{.step = 5, .t = world.time()}, world);
  recorder.Close();

  const std::vector<std::string> lines = ReadLines(dir.path() / "bodies.csv");
  ASSERT_EQ(lines.size(), 3u);
  const std::vector<std::string> expected_names{"box", "body2"};
  for (int id = 1; id <= 2; ++id) {
    const std::vector<std::string> f = SplitCsv(lines[static_cast<std::size_t>(id)]);
    ASSERT_EQ(f.size(), 18u);
    const world::BodyState s = world.body_state(id);
    // Exact comparisons: the CSV must be a lossless copy of the state.
    EXPECT_EQ(Parse(f[0]), world.time());
    EXPECT_EQ(f[1], expected_names[static_cast<std::size_t>(id - 1)]);
    EXPECT_EQ(Vec3(Parse(f[2]), Parse(f[3]), Parse(f[4])), s.X_WB.p);
    EXPECT_EQ(Parse(f[5]), s.X_WB.q.w());
    EXPECT_EQ(Vec3(Parse(f[6]), Parse(f[7]), Parse(f[8])), s.X_WB.q.vec());
    EXPECT_EQ(Vec3(Parse(f[9]), Parse(f[10]), Parse(f[11])), s.V_WCm.v);
    EXPECT_EQ(Vec3(Parse(f[12]), Parse(f[13]), Parse(f[14])), s.V_WCm.w);
    EXPECT_EQ(Vec3(Parse(f[15]), Parse(f[16]), Parse(f[17])), s.p_WCm);
  }
}

// The shipped compound mug: its body frame sits at the scene origin (pos="0 0 0"), but the handle
// (three boxes at x = 4-6.4 cm) pulls the centre of mass off it along x, so the two columns
// groups differ exactly where a user would be misled.
TEST(CsvRecorderTest, BodyColumnsAreTheSceneBodyFrameAndCentreOfMassIsSeparate) {
  const TempDir dir;
  world::World world =
      world::World::LoadFile(std::filesystem::path(MRH_SOURCE_DIR) / "scenes" / "compound_mug.xml");
  CsvRecorder recorder(dir.path());
  recorder.OnStep(physics::StepRecord{}, world);
  recorder.Close();
  const std::vector<std::string> lines = ReadLines(dir.path() / "bodies.csv");
  ASSERT_EQ(lines.size(), 2u);  // the mug; the pointer is mocap, the floor static
  const std::vector<std::string> f = SplitCsv(lines[1]);
  ASSERT_EQ(f.size(), 18u);
  EXPECT_EQ(f[1], "mug");
  // The body origin as written in compound_mug.xml, and the identity orientation.
  EXPECT_EQ(Vec3(Parse(f[2]), Parse(f[3]), Parse(f[4])), Vec3::Zero());
  EXPECT_EQ(Parse(f[5]), 1.0);
  // The handle (about 4 % of the mug's volume, 5.5 cm out) puts the COM about 2 mm towards +x,
  // on the mug's axis in y.
  constexpr double kMm = 1e-3;
  EXPECT_GT(Parse(f[15]), 1 * kMm);
  EXPECT_LT(Parse(f[15]), 3 * kMm);
  EXPECT_NEAR(Parse(f[16]), 0.0, 1e-9);
  EXPECT_GT(Parse(f[17]), 10 * kMm);  // above the base: the wall is 9 cm tall
}

TEST(CsvRecorderTest, DoublesRoundTripExactly) {
  const TempDir dir;
  const std::vector<double> values{1.0 / 3.0,
                                   0.1,
                                   -2.5e17,
                                   1e-300,
                                   std::numeric_limits<double>::denorm_min(),
                                   std::numeric_limits<double>::max(),
                                   std::nextafter(1.0, 2.0),
                                   -0.0};
  CsvRecorder recorder(dir.path());
  for (const double v : values) {
    ir::TickRecord tick;
    tick.t = v;
    tick.displayed_W.f = Vec3(v, -v, v * 0.5);
    recorder.OnTick(tick);
  }
  recorder.Close();
  const std::vector<std::string> lines = ReadLines(dir.path() / "ticks.csv");
  ASSERT_EQ(lines.size(), values.size() + 1);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::vector<std::string> f = SplitCsv(lines[i + 1]);
    // Bit-exact equality is the property under test (fmt prints the shortest exact form).
    EXPECT_EQ(Parse(f[0]), values[i]) << f[0];
    EXPECT_EQ(Parse(f[8]), values[i]) << f[8];
    EXPECT_EQ(Parse(f[9]), -values[i]) << f[9];
    EXPECT_EQ(Parse(f[10]), values[i] * 0.5) << f[10];
  }
}

TEST(CsvRecorderTest, KeepsEveryRowAcrossBufferFlushes) {
  const TempDir dir;
  // ~100 bytes per row: 30 000 rows are ~3 MB, several 1 MB flushes.
  constexpr int kRows = 30000;
  CsvRecorder recorder(dir.path());
  for (int i = 0; i < kRows; ++i) recorder.OnTick(MakeTick(i * 0.001));
  recorder.Close();
  const std::vector<std::string> lines = ReadLines(dir.path() / "ticks.csv");
  ASSERT_EQ(lines.size(), static_cast<std::size_t>(kRows) + 1);
  EXPECT_EQ(Parse(SplitCsv(lines.back())[0]), (kRows - 1) * 0.001);
}

TEST(CsvRecorderTest, UnwritableFolderThrowsNamingThePath) {
  const TempDir dir;
  // A regular file where a folder is needed fails even for root, unlike a chmod'ed folder.
  const std::filesystem::path blocker = dir.path() / "blocker";
  std::ofstream(blocker) << "x";
  const std::filesystem::path out = blocker / "run";
  EXPECT_THAT(
      [&] {
        CsvRecorder recorder(out);
      },
      ThrowsMessage<RuntimeError>(HasSubstr(out.string())));
}

TEST(CsvRecorderTest, UnopenableFileThrowsNamingTheFile) {
  const TempDir dir;
  // A folder where ticks.csv should go cannot be opened as a file.
  std::filesystem::create_directories(dir.path() / "ticks.csv");
  EXPECT_THAT(
      [&] {
        CsvRecorder recorder(dir.path());
      },
      ThrowsMessage<RuntimeError>(HasSubstr((dir.path() / "ticks.csv").string())));
}

TEST(CsvRecorderTest, CloseOnFullDeviceThrowsNamingTheFile) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const TempDir dir;
  // /dev/full accepts open() and fails every write with ENOSPC.
  std::filesystem::create_symlink("/dev/full", dir.path() / "ticks.csv");
  CsvRecorder recorder(dir.path());
  recorder.OnTick(MakeTick(0.0));
  EXPECT_THAT(
      [&] {
        recorder.Close();
      },
      ThrowsMessage<RuntimeError>(HasSubstr("ticks.csv")));
}

}  // namespace
}  // namespace mrh::report
