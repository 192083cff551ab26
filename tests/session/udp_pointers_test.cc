// SPDX-License-Identifier: Apache-2.0
// Two pointers on two UDP ports of loopback, from one session: each pointer's device receives
// its own client's poses and answers that client only.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <thread>
#include <vector>

#include "mrh/device/hardware.h"
#include "mrh/session/session.h"
#include "session/session_test_util.h"

namespace mrh::session {
namespace {

static_assert(std::endian::native == std::endian::little, "the test packs native doubles");

// A client sending pose packets laid out as docs/devices.md specifies (magic "MRHP", version 1,
// sequence, t x y z qw qx qy qz, buttons: 88 bytes) and reading 72-byte wrench packets.
class Client {
 public:
  explicit Client(int port) : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {
    server_.sin_family = AF_INET;
    server_.sin_port = htons(static_cast<std::uint16_t>(port));
    server_.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    timeval two_seconds{2, 0};  // a bound on a lost packet, not a timing measurement
    EXPECT_EQ(::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &two_seconds, sizeof(two_seconds)), 0);
  }

  ~Client() { (void)::close(fd_); }

  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  void SendPose(double x) {
    std::vector<unsigned char> p(88, 0);
    const std::uint32_t version = 1;
    const std::uint64_t seq = 1;
    const double v[8] = {0.0, x, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0};
    std::memcpy(p.data(), "MRHP", 4);
    std::memcpy(p.data() + 4, &version, 4);
    std::memcpy(p.data() + 8, &seq, 8);
    std::memcpy(p.data() + 16, v, sizeof(v));
    ASSERT_EQ(::sendto(fd_, p.data(), p.size(), 0, reinterpret_cast<const sockaddr*>(&server_),
                       sizeof(server_)),
              static_cast<ssize_t>(p.size()));
  }

  // The force x of the next wrench packet, or NaN if none arrives.
  double ReceiveForceX() {
    unsigned char b[128];
    if (::recv(fd_, b, sizeof(b), 0) != 72) return std::nan("");
    double fx = 0.0;
    std::memcpy(&fx, b + 16, sizeof(fx));
    return fx;
  }

 private:
  int fd_;
  sockaddr_in server_{};
};

TEST(UdpPointersTest, EachPointerHasItsOwnPortAndClient) {
  const Session s = testing::Parse(
      R"({"scene": "scene.xml", "method": "single-rate", "pointers": [
          {"body": "f0",
           "device": {"type": "udp", "bind": "127.0.0.1:0", "timeout": 10, "fade": 0}},
          {"body": "f1",
           "device": {"type": "udp", "bind": "127.0.0.1:0", "timeout": 10, "fade": 0}}]})");
  std::unique_ptr<device::Device> devices[2] = {MakePointerDevice(s, 0), MakePointerDevice(s, 1)};
  int ports[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    devices[i]->Open();
    ports[i] = dynamic_cast<device::UdpDevice&>(*devices[i]).bound_port();
  }
  ASSERT_NE(ports[0], ports[1]);
  Client clients[2] = {Client(ports[0]), Client(ports[1])};
  clients[0].SendPose(0.1);
  clients[1].SendPose(0.2);
  // The receiving threads are asynchronous: poll until both poses arrived (bounded).
  double x[2] = {0.0, 0.0};
  for (int k = 0; k < 2000 && (x[0] != 0.1 || x[1] != 0.2); ++k) {
    for (int i = 0; i < 2; ++i) x[i] = devices[i]->Read(0.0).X_DT.p.x();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(x[0], 0.1);
  EXPECT_EQ(x[1], 0.2);
  devices[0]->SetWrench(Wrench{Vec3(1.5, 0, 0), Vec3::Zero()});
  devices[1]->SetWrench(Wrench{Vec3(-2.5, 0, 0), Vec3::Zero()});
  EXPECT_EQ(clients[0].ReceiveForceX(), 1.5);
  EXPECT_EQ(clients[1].ReceiveForceX(), -2.5);
  for (auto& device : devices) device->Close();
}

}  // namespace
}  // namespace mrh::session
