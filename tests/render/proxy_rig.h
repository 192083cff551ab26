// SPDX-License-Identifier: Apache-2.0
// Test rig of the 6-DOF proxy renderer: object pairs written as the interpolator sends them, the
// T3.1 cube pointer (0.2 m) and its gains, and a renderer ticked on them.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "mrh/render/proxy_renderer.h"

namespace mrh::render::proxy_rig {

inline constexpr double kDt = 1e-3;     // haptic period (s)
inline constexpr double kDepth = 1e-3;  // penetration (m)
inline constexpr double kHalf = 0.1;    // half side of the 0.2 m cube pointer (T3.1)
inline constexpr double kKt = 9000.0;   // N/m (T3.1)
inline constexpr double kKr = 9000.0;   // N·m/rad (T3.1)
inline constexpr double kMu = 0.5;      // T3.2
// PGS converges slowly on face and edge contacts when R_w ≫ |r|² (T3.1: 3.33 m² vs 0.02 m²,
// ~1700 sweeps per 1e-7 reduction for 4 points), so the tests solve to 1e-14 m with a budget
// that always suffices; the error in f is then below 1e4 × the last change (rate ≥ 1 − 1e-4),
// i.e. ~1e-10 m, ~1e-6 N of force. Geometry alone is exact to ~1e-15 m.
inline constexpr double kSolverTol = 1e-14;
inline constexpr int kSolverBudget = kMaxProxyIterations;
inline constexpr double kForceTol = kKt * 1e4 * kSolverTol * 10.0;
// Large enough that Δθ is negligible: c_tt − 1 = |r × t|² / R_w ≈ 1e-14.
inline const Mat3 kStiffRotation = 1e12 * Mat3::Identity();

// One object pair: plane and pointer points (pointer frame), as the interpolator would send it.
struct PairSpec {
  std::uint64_t key = 1;
  int body = 0;
  bool is_static = true;
  Pose X_WB;
  Vec3 p_BCm = Vec3::Zero();
  Vec3 n_B = Vec3::UnitZ();  // plane normal in the object frame, object → pointer
  Vec3 p_BC = Vec3::Zero();
  std::vector<Vec3> points_P;
};

// Fills `ir` like IrInterpolator::Evaluate: points re-posed with X_WP, depth = n·(c − v).
inline void Fill(const std::vector<PairSpec>& specs, const Pose& X_WP, TickIr* ir) {
  ir->pairs.Clear();
  ir->points.Clear();
  for (const PairSpec& spec : specs) {
    TickPair pair;
    pair.key = spec.key;
    pair.body = spec.body;
    pair.is_static = spec.is_static;
    pair.X_WB = spec.X_WB;
    pair.p_WCm = spec.X_WB * spec.p_BCm;
    pair.n_W = spec.X_WB.q * spec.n_B;
    pair.c_W = spec.X_WB * spec.p_BC;
    pair.p_BC = spec.p_BC;
    pair.first = static_cast<int>(ir->points.size());
    for (const Vec3& p_PV : spec.points_P) {
      const Vec3 v_W = X_WP * p_PV;
      (void)ir->points.PushBack(
          TickPoint{p_PV, v_W, pair.n_W.dot(pair.c_W - v_W), static_cast<int>(ir->pairs.size())});
    }
    pair.count = static_cast<int>(ir->points.size()) - pair.first;
    (void)ir->pairs.PushBack(pair);
  }
}

inline std::vector<Vec3> BottomFace() {
  return {Vec3(kHalf, kHalf, -kHalf), Vec3(-kHalf, kHalf, -kHalf), Vec3(-kHalf, -kHalf, -kHalf),
          Vec3(kHalf, -kHalf, -kHalf)};
}

inline PairSpec Floor(std::vector<Vec3> points) {
  PairSpec s;
  s.points_P = std::move(points);
  return s;
}

inline ProxyRendererSettings T31() {
  return ProxyRendererSettings{.k_t = kKt,
                               .k_r = kKr,
                               .rotation_weight = 3.33 * Mat3::Identity(),
                               .torque_model = ProxyTorqueModel::kThesis,
                               .max_iterations = kSolverBudget,
                               .tolerance = kSolverTol};
}

inline ProxyRendererSettings Friction(const Mat3& weight = kStiffRotation) {
  ProxyRendererSettings s = T31();
  s.rotation_weight = weight;
  s.mu = kMu;
  return s;
}

// Pointer origin above the floor so its bottom face is kDepth deep, moved and turned.
inline Pose Pressed(const Vec3& shift = Vec3::Zero(), const Quat& q = Quat::Identity()) {
  return Pose{Vec3(0, 0, kHalf - kDepth) + shift, q};
}

inline Quat About(const Vec3& axis, double angle) {
  return Quat(Eigen::AngleAxisd(angle, axis));
}

struct Rig {
  explicit Rig(const ProxyRendererSettings& settings) : renderer(settings) {}

  const ProxyOutput& Tick(const std::vector<PairSpec>& specs, const Pose& X_WP) {
    Fill(specs, X_WP, ir.get());
    renderer.Tick(*ir, X_WP, kDt, out.get());
    return *out;
  }

  ProxyRenderer renderer;
  std::unique_ptr<TickIr> ir = std::make_unique<TickIr>();
  std::unique_ptr<ProxyOutput> out = std::make_unique<ProxyOutput>();
};

inline PairSpec Box(int body, const Pose& X_WB) {
  PairSpec s = Floor(BottomFace());
  s.key = 9;
  s.body = body;
  s.is_static = false;
  s.X_WB = X_WB;
  s.p_BCm = Vec3(0, 0, -0.05);
  return s;
}

}  // namespace mrh::render::proxy_rig
