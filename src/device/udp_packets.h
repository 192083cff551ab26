// SPDX-License-Identifier: Apache-2.0
// The UDP device's packets, little-endian, byte for byte as docs/devices.md gives them.
#pragma once

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "mrh/core/spatial.h"

namespace mrh::device::internal {

/// pose (88 bytes): char[4] "MRHP", u32 version = 1, u64 seq, f64 t, f64 x, y, z,
/// f64 qw, qx, qy, qz, u32 buttons, u32 reserved.
inline constexpr std::size_t kPosePacketSize = 88;
/// wrench (72 bytes): char[4] "MRHW", u32 version = 1, u64 seq, f64 fx, fy, fz, tx, ty, tz,
/// u32 status, u32 reserved.
inline constexpr std::size_t kWrenchPacketSize = 72;
inline constexpr std::uint32_t kUdpProtocolVersion = 1;

struct PosePacket {
  std::uint64_t seq = 0;
  double t = 0.0;
  Pose X_DT;
  std::uint32_t buttons = 0;
};

// Explicit little-endian (de)coding, so the format does not depend on the host's byte order.
inline std::uint64_t LoadLe(const unsigned char* p, int bytes) noexcept {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

inline void StoreLe(unsigned char* p, std::uint64_t v, int bytes) noexcept {
  for (int i = 0; i < bytes; ++i, v >>= 8) p[i] = static_cast<unsigned char>(v & 0xFF);
}

inline double LoadF64(const unsigned char* p) noexcept {
  return std::bit_cast<double>(LoadLe(p, 8));
}

inline void StoreF64(unsigned char* p, double v) noexcept {
  StoreLe(p, std::bit_cast<std::uint64_t>(v), 8);
}

/// Decodes a pose packet. False (the packet is dropped) for a wrong size, magic or version, a
/// non-finite number or a quaternion far from unit length; the quaternion is normalized. RT-safe.
inline bool DecodePose(const unsigned char* data, std::size_t size, PosePacket* out) noexcept {
  // A client's float32 quaternion is unit to ~1e-7; 0.5 only rejects zeros and garbage.
  constexpr double kMinQuatNorm = 0.5;
  if (size != kPosePacketSize || std::memcmp(data, "MRHP", 4) != 0) return false;
  if (LoadLe(data + 4, 4) != kUdpProtocolVersion) return false;
  double v[8];
  for (int i = 0; i < 8; ++i) {
    v[i] = LoadF64(data + 16 + 8 * i);
    if (!std::isfinite(v[i])) return false;
  }
  Quat q(v[4], v[5], v[6], v[7]);
  const double norm = q.norm();
  if (!(norm > kMinQuatNorm && norm < 1.0 / kMinQuatNorm)) return false;
  q.coeffs() /= norm;
  out->seq = LoadLe(data + 8, 8);
  out->t = v[0];
  out->X_DT = Pose{Vec3(v[1], v[2], v[3]), q};
  out->buttons = static_cast<std::uint32_t>(LoadLe(data + 80, 4));
  return true;
}

/// Encodes a wrench packet answering pose `seq`. RT-safe.
inline void EncodeWrench(std::uint64_t seq, const Wrench& w, std::uint32_t status,
                         unsigned char* out) noexcept {
  std::memcpy(out, "MRHW", 4);
  StoreLe(out + 4, kUdpProtocolVersion, 4);
  StoreLe(out + 8, seq, 8);
  const double v[6] = {w.f.x(), w.f.y(), w.f.z(), w.tau.x(), w.tau.y(), w.tau.z()};
  for (int i = 0; i < 6; ++i) StoreF64(out + 16 + 8 * i, v[i]);
  StoreLe(out + 64, status, 4);
  StoreLe(out + 68, 0, 4);
}

}  // namespace mrh::device::internal
