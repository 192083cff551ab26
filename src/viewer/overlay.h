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

/// The coupling the ghost is inferred from (the session's rendering gains).
struct Coupling {
  int pointer_body = -1;
  double stiffness = 0.0;      ///< N/m
  double rot_stiffness = 0.0;  ///< N·m/rad
};

/// The proxy pose the virtual coupling implies: the pose Q at which the coupling springs give the
/// rendered wrench, p_Q = p_P + f/k, R_Q = exp(τ/k_r) R_P (eq. 3.7–3.8 and, for the 3-DOF
/// penalty methods, eq. 4.11: the pointer pushed back to the surface). With damping it includes
/// the damper's share. A zero gain leaves that part of the pose at the pointer's.
Pose InferProxy(const Pose& X_WP, const Wrench& rendered_W, const Coupling& coupling);

/// Adds the debug geoms for the newest tick and IR to `renderer` (after its Update).
void DrawOverlay(world::SceneRenderer& renderer, const TickSample& tick, const IrView& ir,
                 const DisplayOptions& options, const Coupling& coupling);

}  // namespace mrh::viewer::internal
