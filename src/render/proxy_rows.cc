// SPDX-License-Identifier: Apache-2.0
// The proxy's constraint rows for one tick (thesis §3.2.4, steps 2–4): a normal row (eq. 3.1) per
// penetrating point, then its friction row (eq. 3.9–3.10), each warm-started from last tick's f
// when the same row existed (the thesis iterates eq. 3.6 "until f converges", §3.2.2; a warm
// start gets there in fewer sweeps). This is the per-contact cost of a tick, so it is
// one loop over plain arrays.
#include <cmath>
#include <cstdint>

#include "mrh/render/proxy_renderer.h"

namespace mrh::render {
namespace {

// A tangential offset |s| below this is rounding of metre-scale poses (~1e-16 m), not motion:
// no friction row (eq. 3.10 needs a slip direction).
constexpr double kMinSlip = 1e-12;

// Warm-start identity of a row: pair, point index in the tick IR and row kind. Within one
// snapshot the points keep their indices, so a persisting row finds its f; when a new snapshot
// re-derives the points (qhull vertices of the new pose), rows of the same index start from the
// old f, a start like any other (the solvers accept any start).
std::uint64_t RowIdOf(std::uint64_t key, std::size_t point_index, bool friction) noexcept {
  return (key * 0x9e3779b97f4a7c15ULL) ^ (static_cast<std::uint64_t>(point_index) << 1) ^
         (friction ? 1u : 0u);
}

// Appends rows into the renderer's arrays, each with its warm start: last tick's f if the row
// in the same slot had the same id.
struct RowWriter {
  ProxyRow* rows;
  ProxyRowInfo* info;
  std::uint64_t* ids;
  double* f;
  const std::uint64_t* previous_ids;
  const double* previous_f;
  std::size_t capacity;
  std::size_t previous_count;
  std::size_t k = 0;
  int warm = 0;
  bool full = false;

  // False, and `full` set, when every row is taken.
  bool Push(const Vec3& a, const Vec3& r, double rhs, ProxyRowKind kind, int point, int pair,
            std::uint64_t id) noexcept {
    if (k == capacity) {
      full = true;
      return false;
    }
    rows[k].a = a;
    rows[k].r = r;
    rows[k].rhs = rhs;
    info[k] = ProxyRowInfo{kind, point, pair};
    ids[k] = id;
    const bool same = k < previous_count && previous_ids[k] == id;
    f[k] = same ? previous_f[k] : 0.0;
    warm += same ? 1 : 0;
    ++k;
    return true;
  }
};

// A sum of values is finite unless one of them is not (or it overflows, at ~1e308 m), and
// x − x is 0 for finite x and NaN otherwise: the result is NaN iff some value is not finite.
double NanIfBad(const TickPoint& point) noexcept {
  const Vec3& v = point.v_W;
  const double sum = ((point.p_PV.x() + point.p_PV.y()) + (point.p_PV.z() + v.x())) +
                     ((v.y() + v.z()) + point.depth);
  return sum - sum;
}

}  // namespace

// The data of the pair the current points belong to (points come grouped by pair).
struct ProxyRenderer::PairFrame {
  int index = -1;
  Vec3 n = Vec3::UnitZ();
  Vec3 c = Vec3::Zero();
  Vec3 p_WQ = Vec3::Zero();  // the previous proxy, carried with the object
  Mat3 R_WQ = Mat3::Identity();
  std::uint64_t key = 0;
  double mu = 0.0;  // the pair's Coulomb coefficient
  bool with_friction = false;

  // Friction cone of eq. 3.9, the tangential offset of corrected eq. 3.10. With v_q the
  // previous proxy point, v_qs its projection onto the plane and v_ps = v + δn the pointer
  // point's: s = v_qs − v_ps = (v_q − v) − ((v_q − c)·n + δ) n.
  Vec3 Slip(const TickPoint& point) const noexcept {
    const Vec3 v_q = R_WQ * point.p_PV + p_WQ;
    return (v_q - point.v_W) - ((v_q - c).dot(n) + point.depth) * n;
  }
};

bool ProxyRenderer::LoadPair(const TickIr& ir, int pair, PairFrame* frame) const noexcept {
  if (pair < 0 || static_cast<std::size_t>(pair) >= ir.pairs.size()) return false;
  const auto i = static_cast<std::size_t>(pair);
  frame->index = pair;
  frame->n = ir.pairs[i].n_W;
  frame->c = ir.pairs[i].c_W;
  frame->R_WQ = carried_R_WQ_[i];
  frame->p_WQ = carried_p_WQ_[i];
  frame->key = ir.pairs[i].key;
  frame->mu = gains_[i].friction;
  frame->with_friction = frame->mu > 0.0 && !first_tick_[i];
  return true;
}

// One pass over the points, which also checks them: false if any value is not finite.
bool ProxyRenderer::BuildRows(const TickIr& ir, const Pose& X_WP, ProxyDiagnostics* diag) noexcept {
  for (std::size_t i = 0; i < ir.pairs.size(); ++i) pair_rows_[i] = 0;
  RowWriter out{rows_.data(),         info_.data(),       ids_.data(),  f_.data(),
                previous_ids_.data(), previous_f_.data(), rows_.size(), previous_row_count_};
  PairFrame frame;
  int contacts = 0, sticking = 0, sliding = 0;
  double nan_if_bad = 0.0;
  for (std::size_t p = 0; p < ir.points.size(); ++p) {
    const TickPoint& point = ir.points[p];
    nan_if_bad += NanIfBad(point);
    if (!(point.depth > 0.0)) continue;
    if (point.pair != frame.index && !LoadPair(ir, point.pair, &frame)) continue;
    const int index = static_cast<int>(p);
    const Vec3 r = point.v_W - X_WP.p;
    if (!out.Push(frame.n, r, point.depth, ProxyRowKind::kNormal, index, frame.index,
                  RowIdOf(frame.key, p, false))) {
      continue;
    }
    ++contacts;
    ++pair_rows_[static_cast<std::size_t>(frame.index)];
    if (!frame.with_friction) continue;
    const Vec3 s = frame.Slip(point);
    const double slip = s.norm();
    if (!(slip > kMinSlip)) continue;
    const double radius = frame.mu * point.depth;  // ρ_i = μ δ_i
    const bool slides = slip > radius;
    if (out.Push(s * (1.0 / slip), r, slides ? radius : slip,
                 slides ? ProxyRowKind::kSliding : ProxyRowKind::kSticking, index, frame.index,
                 RowIdOf(frame.key, p, true))) {
      ++(slides ? sliding : sticking);
    }
  }
  row_count_ = out.k;
  diag->contacts = contacts;
  diag->sticking_rows = sticking;
  diag->sliding_rows = sliding;
  diag->warm_rows = out.warm;
  if (out.full) diag->status |= kProxyStatusRowsFull;
  return !std::isnan(nan_if_bad);
}

}  // namespace mrh::render
