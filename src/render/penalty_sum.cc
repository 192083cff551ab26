// SPDX-License-Identifier: Apache-2.0
// Baseline B5: per-contact penalty springs summed over the geometric IR (Berkelman & Hollis
// 2000, thesis ref. [43], §3.1.1).
#include "mrh/render/penalty_sum.h"

#include <algorithm>
#include <cmath>

#include "mrh/core/validate.h"

namespace mrh::render {
namespace {

// Identity of a point across ticks: its pair's key mixed with its index in the pair.
std::uint64_t PointId(std::uint64_t pair_key, int index_in_pair) noexcept {
  return pair_key * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(index_in_pair);
}

bool Finite(const Vec3& v) noexcept {
  return v.allFinite();
}

bool InputIsFinite(const TickIr& ir, const Pose& X_WP, double dt) noexcept {
  if (!(dt > 0.0) || !std::isfinite(dt) || !Finite(X_WP.p) || !X_WP.q.coeffs().allFinite()) {
    return false;
  }
  for (const TickPair& pair : ir.pairs) {
    if (!Finite(pair.n_W) || !Finite(pair.p_WCm)) return false;
  }
  for (const TickPoint& point : ir.points) {
    if (!Finite(point.v_W) || !std::isfinite(point.depth)) return false;
  }
  return true;
}

}  // namespace

void PenaltySumSettings::Validate() const {
  RequireNonNegative(k, "PenaltySumSettings.k", "N/m");
  RequireNonNegative(d, "PenaltySumSettings.d", "N·s/m");
}

Wrench PenaltySumWrench(const TickIr& ir, const Pose& X_WP, double k) noexcept {
  Wrench w;
  for (const TickPoint& point : ir.points) {
    if (!(point.depth > 0.0)) continue;
    const Vec3 f = k * point.depth * ir.pairs[static_cast<std::size_t>(point.pair)].n_W;
    w.f += f;
    w.tau += (point.v_W - X_WP.p).cross(f);
  }
  return w;
}

PenaltySumRenderer::PenaltySumRenderer(const PenaltySumSettings& settings) : settings_(settings) {
  settings_.Validate();
}

double PenaltySumRenderer::DepthRate(std::uint64_t id, std::size_t index, double depth,
                                     double dt) const noexcept {
  // Same point at the same slot last tick (the common case), else no rate.
  if (index < previous_count_ && previous_ids_[index] == id) {
    return (depth - previous_depths_[index]) / dt;
  }
  return 0.0;
}

// One pair's penalty forces into out->w_W, its penetrating points into ids_ and depths_ from
// *count on (*count advanced), its reaction into out->reactions.
void PenaltySumRenderer::AddPair(const TickIr& ir, const TickPair& pair, const Pose& X_WP,
                                 double dt, std::size_t* count, PenaltySumOutput* out) noexcept {
  // The object geom's material, or the renderer's k and d.
  const ir::ContactGains g = ir::GainsOf(pair.material, {settings_.k, settings_.d, 0.0});
  Vec3 f_pair = Vec3::Zero();
  Vec3 tau_pair = Vec3::Zero();  // reaction moment about the object's COM
  for (int i = 0; i < pair.count; ++i) {
    const TickPoint& point = ir.points[static_cast<std::size_t>(pair.first + i)];
    if (!(point.depth > 0.0)) continue;
    const std::uint64_t id = PointId(pair.key, i);
    const double rate = DepthRate(id, *count, point.depth, dt);
    ids_[*count] = id;
    depths_[*count] = point.depth;
    ++*count;
    const double magnitude = std::max(0.0, g.stiffness * point.depth + g.damping * rate);
    const Vec3 f = magnitude * pair.n_W;
    out->w_W.f += f;
    out->w_W.tau += (point.v_W - X_WP.p).cross(f);
    f_pair += f;
    tau_pair += (point.v_W - pair.p_WCm).cross(-f);
  }
  Wrench reaction;
  if (!pair.is_static) reaction = Wrench{-f_pair, tau_pair};
  (void)out->reactions.PushBack(ProxyPairReaction{pair.key, pair.body, pair.is_static, reaction});
}

void PenaltySumRenderer::Tick(const TickIr& ir, const Pose& X_WP, double dt,
                              PenaltySumOutput* out) noexcept {
  out->w_W = Wrench{};
  out->reactions.Clear();
  out->contacts = 0;
  out->status = kProxyStatusOk;
  if (!InputIsFinite(ir, X_WP, dt)) {
    out->status = kProxyStatusBadInput;
    Reset();
    return;
  }
  std::size_t count = 0;
  for (const TickPair& pair : ir.pairs) AddPair(ir, pair, X_WP, dt, &count, out);
  out->contacts = static_cast<int>(count);
  std::copy_n(ids_.begin(), count, previous_ids_.begin());
  std::copy_n(depths_.begin(), count, previous_depths_.begin());
  previous_count_ = count;
}

}  // namespace mrh::render
