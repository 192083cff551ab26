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

bool ShowsGhost(const TickSample& tick) {
  return (tick.X_WQ.p - tick.X_WP.p).norm() > kGhostMinOffset ||
         tick.X_WQ.q.angularDistance(tick.X_WP.q) > kGhostMinAngle;
}

void DrawOverlay(world::SceneRenderer& r, const TickSample& tick, const IrView& ir,
                 const DisplayOptions& o, int pointer_body) {
  const Vec3& p = tick.X_WP.p;
  if (o.force) {
    r.AddArrow(p, p + o.force_scale * tick.displayed_W.f, kArrowWidth, kForceColor);
  }
  if (o.torque) {
    r.AddArrow(p, p + o.torque_scale * tick.displayed_W.tau, kArrowWidth, kTorqueColor);
  }
  if (o.ghost && ShowsGhost(tick)) r.AddBodyGhost(pointer_body, tick.X_WQ, kGhostColor);
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
