// SPDX-License-Identifier: Apache-2.0
// Overlay geoms: scaled arrows, a translucent proxy ghost and the IR the haptic thread sees.
#include "viewer/overlay.h"

namespace mrh::viewer::internal {
namespace {

// The ghost is drawn once the proxy is this far from the pointer (m, rad): below it the two
// overlap and the ghost would only flicker.
constexpr double kGhostMinOffset = 2e-4;
constexpr double kGhostMinAngle = 2e-3;
constexpr double kArrowWidth = 0.006;    // m
constexpr double kPointRadius = 0.004;   // m
constexpr double kPlaneHalfSize = 0.04;  // m

constexpr world::Rgba kForceColor{1.0f, 0.35f, 0.1f, 1.0f};
constexpr world::Rgba kTorqueColor{0.7f, 0.3f, 1.0f, 1.0f};
constexpr world::Rgba kGhostColor{0.5f, 0.8f, 1.0f, 0.35f};
constexpr world::Rgba kObjectPointColor{1.0f, 1.0f, 0.2f, 1.0f};
constexpr world::Rgba kPointerPointColor{1.0f, 0.2f, 0.8f, 1.0f};
constexpr world::Rgba kPlaneColor{0.2f, 0.9f, 1.0f, 0.3f};

}  // namespace

Pose InferProxy(const Pose& X_WP, const Wrench& w, const Coupling& c) {
  Pose X_WQ = X_WP;
  if (c.stiffness > 0.0) X_WQ.p += w.f / c.stiffness;
  if (c.rot_stiffness > 0.0) {
    const Vec3 dtheta = w.tau / c.rot_stiffness;
    const double angle = dtheta.norm();
    if (angle > 0.0)
      X_WQ.q = (Quat(Eigen::AngleAxisd(angle, dtheta / angle)) * X_WP.q).normalized();
  }
  return X_WQ;
}

void DrawOverlay(world::SceneRenderer& r, const TickSample& tick, const IrView& ir,
                 const DisplayOptions& o, const Coupling& coupling) {
  const Vec3& p = tick.X_WP.p;
  if (o.force) {
    r.AddArrow(p, p + o.force_scale * tick.displayed_W.f, kArrowWidth, kForceColor);
  }
  if (o.torque) {
    r.AddArrow(p, p + o.torque_scale * tick.displayed_W.tau, kArrowWidth, kTorqueColor);
  }
  if (o.ghost) {
    const Pose X_WQ = InferProxy(tick.X_WP, tick.rendered_W, coupling);
    const double angle = X_WQ.q.angularDistance(tick.X_WP.q);
    if ((X_WQ.p - p).norm() > kGhostMinOffset || angle > kGhostMinAngle) {
      r.AddBodyGhost(coupling.pointer_body, X_WQ, kGhostColor);
    }
  }
  if (o.ir_planes) {
    for (const IrPlane& plane : ir.planes)
      r.AddPlane(plane.p_W, plane.n_W, kPlaneHalfSize, kPlaneColor);
  }
  if (o.ir_points) {
    for (const Vec3& q : ir.object_points_W) r.AddSphere(q, kPointRadius, kObjectPointColor);
    for (const Vec3& q : ir.pointer_points_P) {
      r.AddSphere(tick.X_WP * q, kPointRadius, kPointerPointColor);
    }
  }
}

}  // namespace mrh::viewer::internal
