// SPDX-License-Identifier: Apache-2.0
// PointerTap and WindowForce: per-pointer forces and named bodies' positions of a run.
#include "pointer_tap.h"

#include <algorithm>
#include <cmath>

#include "mrh/core/error.h"
#include "mrh/world/world.h"

namespace mrh::experiments::internal {

void PointerTap::OnTick(const ir::TickRecord& tick) {
  const auto i = static_cast<std::size_t>(tick.pointer);
  if (forces_.size() <= i) forces_.resize(i + 1);
  forces_[i].push_back({tick.t, tick.displayed_W.f});
}

void PointerTap::OnStep(const physics::StepRecord& step, const world::World& world) {
  if (ids_.empty()) {
    for (const std::string& name : names_) {
      const int id = world.FindBody(name);
      if (id < 0) throw InvalidArgument("experiment: the scene has no body \"" + name + "\"");
      ids_.push_back(id);
      masses_.push_back(world.body(id).mass);
    }
  }
  Step s{step.t, {}};
  s.p.reserve(ids_.size());
  for (const int id : ids_) s.p.push_back(world.body_state(id).p_WCm);
  steps_.push_back(std::move(s));
}

const std::vector<PointerTap::Sample>& PointerTap::forces(int i) const {
  static const std::vector<Sample> kNone;
  const auto k = static_cast<std::size_t>(i);
  return k < forces_.size() ? forces_[k] : kNone;
}

ForceStats WindowForce(const std::vector<PointerTap::Sample>& samples, double from, double to) {
  ForceStats s;
  double sum = 0.0, sum2 = 0.0;
  for (const PointerTap::Sample& x : samples) {
    if (x.t < from || x.t > to) continue;
    const double f = x.f.norm();
    sum += f;
    sum2 += f * f;
    s.mean += x.f;
    ++s.n;
  }
  if (s.n == 0) return s;
  s.mean_norm = sum / s.n;
  s.sd_norm = std::sqrt(std::max(0.0, sum2 / s.n - s.mean_norm * s.mean_norm));
  s.mean /= s.n;
  return s;
}

}  // namespace mrh::experiments::internal
