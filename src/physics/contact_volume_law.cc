// SPDX-License-Identifier: Apache-2.0
// Contact-volume penalty law of one convex pair: normal spring–damper and anchored friction.
#include "contact_volume_law.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mrh::physics::internal {
namespace {

struct NormalForce {
  double normal = 0.0;  // N
  Vec3 p_W = Vec3::Zero();
};

// Springhead normalises the pressure integrals by the projected area: the spring gives
// k·V/A_proj (an average depth), the damper d times the average normal approach speed.
NormalForce Normal(const geometry::IntersectionVolume& v, const BodyKinematics& a,
                   const BodyKinematics& b, const PenaltyGains& gains) {
  const std::size_t n_vertices = v.vertices_W.size();
  std::vector<double> depth(n_vertices);
  std::vector<double> approach(n_vertices);
  for (std::size_t k = 0; k < n_vertices; ++k) {
    const Vec3& p = v.vertices_W[k];
    depth[k] = (p - v.c_W).dot(v.n_W);
    approach[k] = -(a.VelocityAt(p) - b.VelocityAt(p)).dot(v.n_W);
  }
  const Wrench spring = geometry::IntegratePressure(v, depth, geometry::PressureSurface::kClosed);
  const Wrench damper = geometry::IntegratePressure(v, approach, geometry::PressureSurface::kUpper);
  const double area = v.projected_area;
  const double spring_n = gains.k * spring.f.dot(v.n_W) / area;
  const double damper_n = gains.d * damper.f.dot(v.n_W) / area;
  // Never pulling: the damper is dropped when it would make the normal force negative.
  const bool damped = spring_n + damper_n >= 0.0;
  NormalForce out;
  out.normal = damped ? spring_n + damper_n : std::max(spring_n, 0.0);
  // Centre of pressure of both terms (the damper's moment damps rocking): the moment about c is
  // r × (N n) with r ⟂ n, so r = n × moment / N.
  Vec3 moment = gains.k * spring.tau / area;
  if (damped) moment += gains.d * damper.tau / area;
  out.p_W = out.normal > 0.0 ? Vec3(v.c_W + v.n_W.cross(moment) / out.normal) : v.c_W;
  return out;
}

Vec3 Tangential(const Vec3& x, const Vec3& n) {
  return x - x.dot(n) * n;
}

// Anchored tangential spring–damper capped at μ N (static while it holds, dynamic once it slid).
Vec3 Friction(const Vec3& n, const NormalForce& normal, const BodyKinematics& a,
              const BodyKinematics& b, const PenaltyGains& gains, FrictionAnchor* anchor) {
  if (!anchor->active) {
    anchor->active = true;
    anchor->sliding = false;
    anchor->p_A = a.X_WB.Inverse() * normal.p_W;
    anchor->p_B = b.X_WB.Inverse() * normal.p_W;
  }
  const Vec3 u = Tangential(a.X_WB * anchor->p_A - b.X_WB * anchor->p_B, n);
  const Vec3 v_t = Tangential(a.VelocityAt(normal.p_W) - b.VelocityAt(normal.p_W), n);
  const Vec3 trial = -gains.k * u - gains.d * v_t;
  const double cap = (anchor->sliding ? gains.mu_dynamic : gains.mu_static) * normal.normal;
  const double size = trial.norm();
  if (size <= cap) {
    anchor->sliding = false;
    return trial;
  }
  anchor->sliding = true;
  const double cap_k = gains.mu_dynamic * normal.normal;
  const Vec3 f = size > 0.0 ? Vec3(trial * (cap_k / size)) : Vec3::Zero();
  // Slide A's anchor so the spring alone carries the dynamic cap: u' = −f / k.
  const Vec3 u_new = gains.k > 0.0 ? Vec3(-f / gains.k) : Vec3::Zero();
  anchor->p_A = a.X_WB.Inverse() * (b.X_WB * anchor->p_B + u_new);
  return f;
}

}  // namespace

PairForce ContactVolumeForce(const geometry::IntersectionVolume& v, const BodyKinematics& a,
                             const BodyKinematics& b, const PenaltyGains& gains,
                             FrictionAnchor* anchor) {
  const NormalForce normal = Normal(v, a, b, gains);
  PairForce out;
  out.normal = normal.normal;
  out.p_W = normal.p_W;
  out.f_W = normal.normal * v.n_W;
  if (gains.mu_static > 0.0 || gains.mu_dynamic > 0.0) {
    out.f_W += Friction(v.n_W, normal, a, b, gains, anchor);
  }
  out.sliding = anchor->sliding;
  return out;
}

}  // namespace mrh::physics::internal
