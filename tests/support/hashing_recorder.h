// SPDX-License-Identifier: Apache-2.0
// A Recorder that hashes a run: the golden-hash and rerun-identity tests of every method.
#pragma once

#include <cstdint>
#include <cstring>

#include "mrh/ir/tick_record.h"
#include "mrh/physics/recorder.h"
#include "mrh/world/world.h"

namespace mrh::testing {

/// FNV-1a over the raw bytes of every recorded double: per tick t, the pointer position, the
/// rendered and displayed forces; per step the world's qpos and qvel. Any bit that changes
/// changes the hash, so two lockstep runs are bit-identical iff their hashes are (up to a 2⁻⁶⁴
/// collision).
class HashingRecorder final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& t) override {
    Add(t.t);
    for (int i = 0; i < 3; ++i) Add(t.X_WP.p[i]);
    for (int i = 0; i < 3; ++i) Add(t.rendered_W.f[i]);
    for (int i = 0; i < 3; ++i) Add(t.displayed_W.f[i]);
  }

  void OnStep(const physics::StepRecord&, const world::World& world) override {
    for (double q : world.qpos()) Add(q);
    for (double v : world.qvel()) Add(v);
  }

  std::uint64_t hash() const { return hash_; }

 private:
  void Add(double value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    for (int i = 0; i < 8; ++i) {
      hash_ ^= (bits >> (8 * i)) & 0xffu;
      hash_ *= 0x100000001b3ull;
    }
  }

  std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

}  // namespace mrh::testing
