// SPDX-License-Identifier: Apache-2.0
// Draws a world's scene with MuJoCo's own OpenGL renderer, plus debug geoms (viewer builds only).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <utility>
#include <vector>

#include "mrh/core/spatial.h"

namespace mrh::world {

class World;

/// A colour; each channel in [0, 1], a < 1 is drawn transparent.
struct Rgba {
  float r = 1.0f, g = 1.0f, b = 1.0f, a = 1.0f;
};

/// The state a drawing needs: joint coordinates and the poses of mocap bodies (world frame).
struct SceneState {
  double t = 0.0;                           ///< simulation time (s)
  std::vector<double> qpos;                 ///< World::qpos()
  std::vector<std::pair<int, Pose>> mocap;  ///< (body id, X_WB) of every mocap body
};

/// Copies what SceneRenderer::Update needs from `world`. Call it on the thread that owns the
/// world. Allocates only while `state` grows (the first call). Not RT-safe.
void CaptureSceneState(const World& world, SceneState* state);

/// An orbit camera, as in MuJoCo's simulate: it looks at `lookat` from `distance`.
struct OrbitCamera {
  Vec3 lookat = Vec3::Zero();  ///< m, world frame
  double distance = 1.0;       ///< m
  double azimuth_deg = 90.0;   ///< about world z
  double elevation_deg = -30.0;
};

/// Camera motions of MuJoCo's simulate viewer (mjv_moveCamera).
enum class CameraMotion {
  kRotateVertical,    ///< orbit about the camera's right and world-up axes
  kRotateHorizontal,  ///< orbit in the horizontal plane only
  kMoveVertical,      ///< pan in the view plane
  kMoveHorizontal,    ///< pan in the horizontal plane
  kZoom,              ///< change the distance
};

/// Where the camera was at the last Update(), world frame: to turn mouse motion into motion.
struct CameraFrame {
  Vec3 p_WC = Vec3::Zero();         ///< eye position (m)
  Vec3 forward_W = -Vec3::UnitZ();  ///< unit view direction
  Vec3 up_W = Vec3::UnitY();        ///< unit up direction, orthogonal to forward_W
  /// Height of the view frustum at unit distance (dimensionless, = 2 tan(fovy/2)).
  double frustum_height = 1.0;
};

/// Settings of a SceneRenderer.
struct SceneRendererSettings {
  /// Geoms per frame, scene and debug geoms together; debug geoms beyond it are dropped.
  int max_geoms = 4000;
  /// Text scale for MuJoCo's fonts (percent: 100, 150, 200, ...), from the display's DPI scale.
  int font_scale = 100;
};

/// Draws a scene: its own copy of the MJCF model, posed from SceneState snapshots, plus debug
/// geoms (arrows, spheres, planes, ghost bodies) added per frame. Every call must come from the
/// thread on which the OpenGL context it was created with is current. Not RT-safe.
class SceneRenderer {
 public:
  /// Loads `mjcf` for drawing and creates MuJoCo's GL resources. @pre an OpenGL (compatibility
  /// profile) context is current. @throws mrh::SceneError if the file does not load.
  explicit SceneRenderer(const std::filesystem::path& mjcf,
                         const SceneRendererSettings& settings = {});
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  /// The camera; change it freely between frames.
  OrbitCamera& camera();
  /// Frames the whole model (MuJoCo's default free camera).
  void ResetCamera();
  /// Points the camera at the bounding sphere of the geoms of `bodies` (posed by the last
  /// Update; planes excluded) from a distance that fits it in view, keeping azimuth and
  /// elevation. Ids out of range are ignored; with no geoms the camera is unchanged.
  void FrameBodies(const std::vector<int>& bodies);
  /// Moves the camera by a mouse displacement (dx, dy) in units of the viewport height.
  void MoveCamera(CameraMotion motion, double dx, double dy);
  /// The camera of the last Update() (the default camera before the first).
  CameraFrame camera_frame() const;

  /// Poses the model from `state` and rebuilds the scene for the camera; removes the debug geoms.
  /// State of the wrong size (another scene) is ignored and the previous poses stay.
  void Update(const SceneState& state);

  /// Debug geoms for this frame (after Update). Each returns false if the scene is full.
  /// An arrow from `from_W` to `to_W` (m); `width` is its shaft diameter (m).
  bool AddArrow(const Vec3& from_W, const Vec3& to_W, double width, const Rgba& color);
  bool AddSphere(const Vec3& p_W, double radius, const Rgba& color);
  /// A square of half-size `half_size` (m) through p_W, normal n_W (unit), drawn as a thin slab.
  bool AddPlane(const Vec3& p_W, const Vec3& n_W, double half_size, const Rgba& color);
  /// The geoms of `body` drawn again at pose X_WB in `color` (a ghost). Returns false if the
  /// body is out of range or the scene is full.
  bool AddBodyGhost(int body, const Pose& X_WB, const Rgba& color);

  /// Renders into the current framebuffer's viewport (0, 0, width, height), in framebuffer pixels.
  void Render(int width, int height);
  /// Reads the current framebuffer's (0, 0, width, height) as RGB bytes, top row first.
  std::vector<std::uint8_t> ReadPixels(int width, int height) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mrh::world
