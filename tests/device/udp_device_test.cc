// SPDX-License-Identifier: Apache-2.0
// The udp device over loopback: a client in the test packs poses byte by byte as
// docs/devices.md specifies and reads the wrench packets back.
#include <arpa/inet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <thread>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/device/hardware.h"

namespace mrh::device {
namespace {

static_assert(std::endian::native == std::endian::little, "the test packs native doubles");

constexpr double kTol = 1e-12;

// The test's own packing (offsets from the protocol table, not from the code under test).
std::vector<unsigned char> PosePacket(std::uint64_t seq, const double v[8], std::uint32_t buttons,
                                      const char* magic = "MRHP", std::uint32_t version = 1) {
  std::vector<unsigned char> p(88, 0);
  std::memcpy(p.data(), magic, 4);
  std::memcpy(p.data() + 4, &version, 4);
  std::memcpy(p.data() + 8, &seq, 8);
  std::memcpy(p.data() + 16, v, 8 * sizeof(double));  // t, x, y, z, qw, qx, qy, qz
  std::memcpy(p.data() + 80, &buttons, 4);
  return p;
}

struct WrenchPacket {
  char magic[5] = {};
  std::uint32_t version = 0;
  std::uint64_t seq = 0;
  double w[6] = {};
  std::uint32_t status = 0;
};

class Client {
 public:
  explicit Client(int server_port) : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {
    server_.sin_family = AF_INET;
    server_.sin_port = htons(static_cast<std::uint16_t>(server_port));
    server_.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    timeval two_seconds{2, 0};  // a bound on a lost packet, not a timing measurement
    EXPECT_EQ(::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &two_seconds, sizeof(two_seconds)), 0);
  }

  ~Client() { (void)::close(fd_); }

  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  void Send(const std::vector<unsigned char>& bytes) {
    ASSERT_EQ(::sendto(fd_, bytes.data(), bytes.size(), 0,
                       reinterpret_cast<const sockaddr*>(&server_), sizeof(server_)),
              static_cast<ssize_t>(bytes.size()));
  }

  bool Receive(WrenchPacket* out) {
    unsigned char b[128];
    const ssize_t n = ::recv(fd_, b, sizeof(b), 0);
    if (n != 72) return false;
    std::memcpy(out->magic, b, 4);
    std::memcpy(&out->version, b + 4, 4);
    std::memcpy(&out->seq, b + 8, 8);
    std::memcpy(out->w, b + 16, 48);
    std::memcpy(&out->status, b + 64, 4);
    return true;
  }

 private:
  int fd_;
  sockaddr_in server_{};
};

// The receiving thread is asynchronous: poll the device until the pose shows up (bounded).
bool WaitFor(const std::function<bool()>& done) {
  for (int i = 0; i < 2000; ++i) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

std::unique_ptr<UdpDevice> OpenDevice(double timeout, double fade, bool has_torque = true) {
  Specifications specs;
  specs.has_torque = has_torque;
  auto device = MakeUdpDevice(UdpSettings{"127.0.0.1:0", timeout, fade}, specs);
  device->Open();
  return device;
}

TEST(UdpDeviceTest, PosesInWrenchesOutAnsweringTheSequenceNumber) {
  auto device = OpenDevice(10.0, 0.0);
  Client client(device->bound_port());
  const double s = std::sqrt(0.5);
  const double pose[8] = {0.25, 0.01, 0.02, 0.03, s, 0, 0, s};  // 90 degrees about z
  client.Send(PosePacket(41, pose, 3));
  DeviceState state;
  ASSERT_TRUE(WaitFor([&] {
    return (state = device->Read(0.0)).X_DT.p.x() == 0.01;
  }));
  EXPECT_NEAR((state.X_DT.p - Vec3(0.01, 0.02, 0.03)).norm(), 0.0, kTol);
  EXPECT_NEAR((state.X_DT.q * Vec3::UnitX() - Vec3::UnitY()).norm(), 0.0, kTol);
  EXPECT_EQ(state.buttons, 3u);

  device->SetSafetyBits(1u << 2);  // kSafetyForceClamped
  device->SetWrench(Wrench{Vec3(1, -2, 3), Vec3(0.1, 0.2, 0.3)});
  WrenchPacket w;
  ASSERT_TRUE(client.Receive(&w));
  EXPECT_STREQ(w.magic, "MRHW");
  EXPECT_EQ(w.version, 1u);
  EXPECT_EQ(w.seq, 41u);
  const double expected[6] = {1, -2, 3, 0.1, 0.2, 0.3};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(w.w[i], expected[i]);
  EXPECT_EQ(w.status, 1u << 2);
  EXPECT_EQ(device->counters().wrenches_sent, 1);
}

TEST(UdpDeviceTest, TheNewestPoseWins) {
  auto device = OpenDevice(10.0, 0.0);
  Client client(device->bound_port());
  for (int i = 1; i <= 5; ++i) {
    const double pose[8] = {0, 0.001 * i, 0, 0, 1, 0, 0, 0};
    client.Send(PosePacket(static_cast<std::uint64_t>(i), pose, 0));
  }
  ASSERT_TRUE(WaitFor([&] {
    return device->counters().poses_received == 5;
  }));
  EXPECT_DOUBLE_EQ(device->Read(0.0).X_DT.p.x(), 0.005);
}

TEST(UdpDeviceTest, MalformedAndForeignPacketsAreCountedAndDropped) {
  auto device = OpenDevice(10.0, 0.0);
  Client client(device->bound_port());
  const double good[8] = {0, 0.01, 0, 0, 1, 0, 0, 0};
  client.Send(PosePacket(1, good, 0));
  ASSERT_TRUE(WaitFor([&] {
    return device->Read(0.0).X_DT.p.x() == 0.01;
  }));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double bad_value[8] = {0, nan, 0, 0, 1, 0, 0, 0};
  const double zero_quat[8] = {0, 0.02, 0, 0, 0, 0, 0, 0};
  std::vector<unsigned char> too_short = PosePacket(2, good, 0);
  too_short.resize(40);
  std::vector<unsigned char> too_long = PosePacket(2, good, 0);
  too_long.push_back(0);
  client.Send(too_short);
  client.Send(too_long);
  client.Send(PosePacket(3, good, 0, "OSC/"));
  client.Send(PosePacket(4, good, 0, "MRHP", 2));
  client.Send(PosePacket(5, bad_value, 0));
  client.Send(PosePacket(6, zero_quat, 0));
  ASSERT_TRUE(WaitFor([&] {
    return device->counters().packets_malformed == 6;
  }));
  EXPECT_EQ(device->counters().poses_received, 1);
  EXPECT_DOUBLE_EQ(device->Read(0.0).X_DT.p.x(), 0.01);  // still the good pose
}

TEST(UdpDeviceTest, NoPoseForTheTimeoutFadesTheForceToZeroAndIsCounted) {
  constexpr double kTimeout = 0.01, kFade = 0.01;
  auto device = OpenDevice(kTimeout, kFade);
  Client client(device->bound_port());
  const double pose[8] = {0, 0.01, 0, 0, 1, 0, 0, 0};
  client.Send(PosePacket(9, pose, 0));
  ASSERT_TRUE(WaitFor([&] {
    return device->Read(0.0).X_DT.p.x() == 0.01;
  }));
  // Well past timeout + fade: one read moves the gain by elapsed / fade, far more than 1.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  (void)device->Read(0.1);
  device->SetWrench(Wrench{Vec3(5, 0, 0), Vec3::Zero()});
  WrenchPacket w;
  ASSERT_TRUE(client.Receive(&w));
  EXPECT_EQ(w.w[0], 0.0);
  EXPECT_NE(w.status & kUdpPoseTimeout, 0u);
  EXPECT_GE(device->counters().pose_timeouts, 1);
}

TEST(UdpDeviceTest, AThreeDofDeviceSendsNoTorqueAndFlagsIt) {
  auto device = OpenDevice(10.0, 0.0, /*has_torque=*/false);
  Client client(device->bound_port());
  const double pose[8] = {0, 0.01, 0, 0, 1, 0, 0, 0};
  client.Send(PosePacket(1, pose, 0));
  ASSERT_TRUE(WaitFor([&] {
    return device->Read(0.0).X_DT.p.x() == 0.01;
  }));
  device->SetWrench(Wrench{Vec3(1, 0, 0), Vec3(0, 0, 0.2)});
  WrenchPacket w;
  ASSERT_TRUE(client.Receive(&w));
  EXPECT_EQ(w.w[0], 1.0);
  EXPECT_EQ(w.w[5], 0.0);
  EXPECT_NE(w.status & kUdpTorqueDropped, 0u);
  EXPECT_EQ(device->counters().torque_dropped, 1);
}

TEST(UdpDeviceTest, BeforeAnyPoseNothingIsSentAndNothingIsCountedAsTimeout) {
  auto device = OpenDevice(0.01, 0.0);
  (void)device->Read(0.0);
  device->SetWrench(Wrench{Vec3(1, 0, 0), Vec3::Zero()});
  EXPECT_EQ(device->counters().wrenches_sent, 0);
  EXPECT_EQ(device->counters().pose_timeouts, 0);
}

TEST(UdpDeviceTest, ABadBindIsAnErrorNamingTheValue) {
  for (const char* bind : {"127.0.0.1", "nohost:47800", "127.0.0.1:99999", "127.0.0.1:x"}) {
    EXPECT_THAT(
        [&] {
          CheckUdpBind(bind);
        },
        ::testing::ThrowsMessage<InvalidArgument>(::testing::HasSubstr(bind)));
  }
}

TEST(UdpDeviceTest, ABusyPortIsAnErrorNamingTheBindAddress) {
  auto first = OpenDevice(1.0, 0.0);
  const std::string bind = "127.0.0.1:" + std::to_string(first->bound_port());
  auto second = MakeUdpDevice(UdpSettings{bind, 1.0, 0.0}, {});
  EXPECT_THAT(
      [&] {
        second->Open();
      },
      ::testing::ThrowsMessage<RuntimeError>(::testing::HasSubstr(bind)));
}

}  // namespace
}  // namespace mrh::device
