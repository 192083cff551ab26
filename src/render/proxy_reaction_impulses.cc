// SPDX-License-Identifier: Apache-2.0
// The proxy's per-pair reactions summed per body into the period's impulses (applied by the
// next physics step, thesis §3.5).
#include <array>

#include "mrh/render/proxy_renderer.h"

namespace mrh::render {

void AddReactionImpulses(const ProxyOutput& out, double dt, ir::HapticReport* report) noexcept {
  AddReactionImpulses(out.reactions, dt, report);
}

void AddReactionImpulses(const FixedVector<ProxyPairReaction, ir::kMaxGeometricPairs>& reactions,
                         double dt, ir::HapticReport* report) noexcept {
  // Sum this tick's reactions per body first, so last_force is the body's whole force.
  std::array<int, ir::kMaxGeometricPairs> bodies{};
  std::array<Wrench, ir::kMaxGeometricPairs> sums{};
  std::size_t count = 0;
  for (const ProxyPairReaction& r : reactions) {
    if (r.is_static || r.body < 0) continue;
    std::size_t b = 0;
    while (b < count && bodies[b] != r.body) ++b;
    if (b == count) bodies[count++] = r.body;
    sums[b].f += r.w_W.f;
    sums[b].tau += r.w_W.tau;
  }
  for (ir::BodyImpulse& entry : report->impulses) entry.last_force = Vec3::Zero();
  for (std::size_t b = 0; b < count; ++b) {
    if (sums[b].f.isZero(0.0) && sums[b].tau.isZero(0.0)) continue;
    report->AddImpulse(bodies[b], sums[b].f * dt, sums[b].tau * dt, sums[b].f);
  }
}

}  // namespace mrh::render
