// SPDX-License-Identifier: Apache-2.0
// The network device: poses in, wrenches out over UDP; a receiving thread that never blocks
// the haptic tick, newest pose wins, a timeout watchdog that fades the force.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>
#include <thread>

#include "device/hardware_impl.h"
#include "device/udp_packets.h"
#include "mrh/core/error.h"
#include "mrh/core/triple_buffer.h"
#include "mrh/core/validate.h"
#include "mrh/device/hardware.h"
#include "mrh/device/safety.h"

namespace mrh::device {
namespace {

// How often the receiving thread looks at its quit flag while no packet arrives.
constexpr int kReceivePollMs = 20;

std::int64_t SteadyNs() noexcept {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

sockaddr_in ParseBind(const std::string& bind) {
  const std::string expected =
      "; expected \"host:port\" with an IPv4 host (e.g. "
      "\"127.0.0.1:47800\", \"0.0.0.0:47800\") and a port 0..65535";
  const std::size_t colon = bind.rfind(':');
  if (colon == std::string::npos) {
    throw InvalidArgument("device.bind = \"" + bind + "\": no port" + expected);
  }
  std::string host = bind.substr(0, colon);
  const std::string port_text = bind.substr(colon + 1);
  if (host == "localhost") host = "127.0.0.1";
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  if (::inet_pton(AF_INET, host.c_str(), &addr.sin_addr) != 1) {
    throw InvalidArgument("device.bind = \"" + bind + "\": bad host \"" + host + "\"" + expected);
  }
  const bool digits = !port_text.empty() && port_text.size() <= 5 &&
                      std::all_of(port_text.begin(), port_text.end(), [](char c) {
                        return c >= '0' && c <= '9';
                      });
  const int port = digits ? std::stoi(port_text) : -1;
  if (port < 0 || port > 65535) {
    throw InvalidArgument("device.bind = \"" + bind + "\": bad port \"" + port_text + "\"" +
                          expected);
  }
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  return addr;
}

// What the receiving thread hands to the haptic thread.
struct Received {
  std::uint64_t serial = 0;  // count of good packets: tells a new pose from the old one
  std::int64_t rx_ns = 0;    // steady clock at reception
  internal::PosePacket pose;
  sockaddr_in from{};
};

class UdpDeviceImpl final : public UdpDevice {
 public:
  UdpDeviceImpl(const UdpSettings& settings, const Specifications& specs)
      : settings_(settings), specs_(specs), addr_(ParseBind(settings.bind)) {
    if (!(settings.timeout > 0.0) || !std::isfinite(settings.timeout)) {
      throw InvalidArgument("device.timeout = " + FormatNumber(settings.timeout) +
                            " s; expected a number > 0");
    }
    if (!(settings.fade >= 0.0) || !std::isfinite(settings.fade)) {
      throw InvalidArgument("device.fade = " + FormatNumber(settings.fade) +
                            " s; expected a number >= 0");
    }
  }

  ~UdpDeviceImpl() override { Close(); }

  const Specifications& specifications() const override { return specs_; }

  int bound_port() const override { return port_; }

  DeviceCounters counters() const override { return counters_.Load(); }

  void Open() override;
  void Close() override;
  DeviceState Read(double t) noexcept override;
  void SetWrench(const Wrench& w_D) noexcept override;

  void SetSafetyBits(std::uint32_t bits) noexcept override { safety_bits_ = bits; }

 private:
  void Receive() noexcept;
  void UpdateWatchdog(std::int64_t now_ns) noexcept;

  UdpSettings settings_;
  Specifications specs_;
  sockaddr_in addr_;
  int fd_ = -1;
  int port_ = 0;
  std::thread receiver_;
  std::atomic<bool> quit_{false};
  TripleBuffer<Received> inbox_;  // receiving thread → haptic thread
  internal::AtomicCounters counters_;
  // Haptic thread only:
  std::uint64_t serial_ = 0;
  Received latest_;
  bool have_sender_ = false;
  std::int64_t last_read_ns_ = 0;
  double gain_ = 0.0;
  std::uint32_t status_ = 0;
  std::uint32_t safety_bits_ = 0;
};

void UdpDeviceImpl::Open() {
  if (fd_ >= 0) return;
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw RuntimeError(std::string("udp device: socket(): ") + std::strerror(errno));
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&addr_), sizeof(addr_)) != 0) {
    const std::string why = std::strerror(errno);
    (void)::close(fd_);
    fd_ = -1;
    throw RuntimeError("udp device: cannot bind device.bind = \"" + settings_.bind + "\": " + why +
                       " (is another mrh or program using the port?)");
  }
  sockaddr_in bound{};
  socklen_t length = sizeof(bound);
  if (::getsockname(fd_, reinterpret_cast<sockaddr*>(&bound), &length) == 0) {
    port_ = ntohs(bound.sin_port);
  }
  quit_.store(false);
  last_read_ns_ = SteadyNs();
  receiver_ = std::thread([this] {
    Receive();
  });
}

void UdpDeviceImpl::Close() {
  if (fd_ < 0) return;
  SetWrench(Wrench{});  // a last zero wrench, so the client does not hold the previous one
  quit_.store(true);
  if (receiver_.joinable()) receiver_.join();
  (void)::close(fd_);  // nothing useful to do if close fails on a datagram socket
  fd_ = -1;
}

// The receiving thread: waits on the socket (never the haptic thread), decodes, publishes.
void UdpDeviceImpl::Receive() noexcept {
  std::uint64_t serial = 0;
  // One byte more than a pose, so an oversized datagram shows as the wrong size.
  unsigned char buffer[internal::kPosePacketSize + 1];
  while (!quit_.load(std::memory_order_relaxed)) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, kReceivePollMs) <= 0) continue;
    sockaddr_in from{};
    socklen_t from_length = sizeof(from);
    const ssize_t n = ::recvfrom(fd_, buffer, sizeof(buffer), MSG_DONTWAIT,
                                 reinterpret_cast<sockaddr*>(&from), &from_length);
    if (n < 0) continue;  // EAGAIN or a transient error: poll again
    Received& slot = inbox_.write_slot();
    if (!internal::DecodePose(buffer, static_cast<std::size_t>(n), &slot.pose)) {
      internal::AtomicCounters::Bump(counters_.packets_malformed);
      continue;
    }
    slot.serial = ++serial;
    slot.rx_ns = SteadyNs();
    slot.from = from;
    inbox_.Publish();
    internal::AtomicCounters::Bump(counters_.poses_received);
  }
}

// Watchdog: after `timeout` without a pose the gain falls to 0 over `fade` (wall clock, as the
// client's stream is), and climbs back the same way once poses return.
void UdpDeviceImpl::UpdateWatchdog(std::int64_t now_ns) noexcept {
  const double dt = std::max(0.0, 1e-9 * static_cast<double>(now_ns - last_read_ns_));
  last_read_ns_ = now_ns;
  const double age = 1e-9 * static_cast<double>(now_ns - latest_.rx_ns);
  const bool fresh = have_sender_ && age <= settings_.timeout;
  if (have_sender_ && !fresh) internal::AtomicCounters::Bump(counters_.pose_timeouts);
  const double target = fresh ? 1.0 : 0.0;
  if (settings_.fade == 0.0) {
    gain_ = target;
  } else {
    const double step = dt / settings_.fade;
    gain_ = std::clamp(target, gain_ - step, gain_ + step);
  }
  status_ = gain_ < 1.0 ? static_cast<std::uint32_t>(kUdpPoseTimeout) : 0u;
}

DeviceState UdpDeviceImpl::Read(double t) noexcept {
  if (inbox_.Update() && inbox_.read_slot().serial != serial_) {
    latest_ = inbox_.read_slot();
    serial_ = latest_.serial;
    have_sender_ = true;
  }
  UpdateWatchdog(SteadyNs());
  DeviceState s;
  s.t = t;
  s.X_DT = latest_.pose.X_DT;  // the newest pose, held while none arrives
  s.buttons = latest_.pose.buttons;
  return s;
}

void UdpDeviceImpl::SetWrench(const Wrench& w_D) noexcept {
  if (!have_sender_ || fd_ < 0) return;  // nobody to answer yet
  const std::int64_t dropped_before = counters_.torque_dropped.load(std::memory_order_relaxed);
  Wrench w = internal::DropTorqueIfNoTorque(specs_, w_D, &counters_);
  std::uint32_t status = safety_bits_ | status_;
  if (counters_.torque_dropped.load(std::memory_order_relaxed) != dropped_before) {
    status |= kUdpTorqueDropped;
  }
  w.f *= gain_;
  w.tau *= gain_;
  unsigned char packet[internal::kWrenchPacketSize];
  internal::EncodeWrench(latest_.pose.seq, w, status, packet);
  // Non-blocking: a full socket buffer loses this packet (the next tick sends a newer one).
  const ssize_t sent =
      ::sendto(fd_, packet, sizeof(packet), MSG_DONTWAIT,
               reinterpret_cast<const sockaddr*>(&latest_.from), sizeof(latest_.from));
  if (sent == static_cast<ssize_t>(sizeof(packet))) {
    internal::AtomicCounters::Bump(counters_.wrenches_sent);
  }
}

}  // namespace

void CheckUdpBind(const std::string& bind) {
  (void)ParseBind(bind);
}

std::unique_ptr<UdpDevice> MakeUdpDevice(const UdpSettings& settings, const Specifications& specs) {
  return std::make_unique<UdpDeviceImpl>(settings, specs);
}

}  // namespace mrh::device
