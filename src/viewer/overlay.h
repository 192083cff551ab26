// SPDX-License-Identifier: Apache-2.0
// What the viewer draws over the scene: wrench arrows, the proxy ghost, IR points and planes.
#pragma once

#include "mrh/world/scene_renderer.h"
#include "viewer/live_feed.h"

namespace mrh::viewer::internal {

/// Display toggles and scales, edited in the panel.
struct DisplayOptions {
  bool force = true;          ///< displayed force arrow at the pointer
  bool torque = true;         ///< displayed torque arrow at the pointer
  bool ghost = true;          ///< the proxy, where it differs from the pointer
  bool ir_points = true;      ///< contact points of the current IR
  bool ir_planes = false;     ///< planes of the current IR
  float force_scale = 0.02f;  ///< arrow length per newton (m/N)
  float torque_scale = 0.2f;  ///< arrow length per newton metre (m/(N·m))
  float plot_seconds = 5.0f;  ///< time window of the plots (s)
  bool camera_drag = false;   ///< plain drags move the camera (Ctrl: the pointer)
  bool panel = true;          ///< draw the ImGui panel
};

/// True if the tick's proxy X_WQ (the method's own, engine::TickRecord::X_WQ) is far enough
/// from the pointer X_WP to be drawn as a ghost: more than 0.2 mm or 2 mrad apart. Methods
/// without a proxy report the pointer pose, so they never show one.
bool ShowsGhost(const TickSample& tick);

/// Adds the debug geoms for the newest tick and IR to `renderer` (after its Update); the ghost
/// is the body `pointer_body` drawn at the tick's proxy pose.
void DrawOverlay(world::SceneRenderer& renderer, const TickSample& tick, const IrView& ir,
                 const DisplayOptions& options, int pointer_body);

}  // namespace mrh::viewer::internal
