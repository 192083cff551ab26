// SPDX-License-Identifier: Apache-2.0
// SceneRenderer over MuJoCo 2.2's mjv_/mjr_ API: a private model copy posed from snapshots.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "mrh/core/error.h"
#include "mrh/world/scene_renderer.h"
#include "mrh/world/world.h"
#include "world/world_impl.h"

namespace mrh::world {
namespace {

// Slab thickness of a drawn IR plane, relative to its half-size: thin but never z-fighting.
constexpr double kPlaneThicknessRatio = 0.01;
// FrameBodies leaves this much room around the framed bounding sphere (ratio of its radius): 1
// fits its height in the view exactly, and views are wider than tall.
constexpr double kFrameMargin = 1.05;
// Arrows shorter than this (m) are not drawn: MuJoCo cannot orient a zero-length connector.
constexpr double kMinArrowLength = 1e-6;

// MuJoCo's fonts exist at 50 %, 100 %, ... 300 %; take the nearest.
int NearestFontScale(int percent) {
  const int rounded = static_cast<int>(std::lround(percent / 50.0)) * 50;
  return std::clamp(rounded, static_cast<int>(mjFONTSCALE_50), static_cast<int>(mjFONTSCALE_300));
}

// mjvGeom stores row-major 3×3 float matrices.
void SetPose(mjvGeom* g, const Vec3& p, const Mat3& R) {
  for (int i = 0; i < 3; ++i) {
    g->pos[i] = static_cast<float>(p[i]);
    for (int j = 0; j < 3; ++j) g->mat[3 * i + j] = static_cast<float>(R(i, j));
  }
}

int ToMujoco(CameraMotion motion) {
  switch (motion) {
    case CameraMotion::kRotateVertical:
      return mjMOUSE_ROTATE_V;
    case CameraMotion::kRotateHorizontal:
      return mjMOUSE_ROTATE_H;
    case CameraMotion::kMoveVertical:
      return mjMOUSE_MOVE_V;
    case CameraMotion::kMoveHorizontal:
      return mjMOUSE_MOVE_H;
    case CameraMotion::kZoom:
      return mjMOUSE_ZOOM;
  }
  return mjMOUSE_NONE;
}

}  // namespace

void CaptureSceneState(const World& world, SceneState* state) {
  state->t = world.time();
  const std::span<const double> qpos = world.qpos();
  state->qpos.assign(qpos.begin(), qpos.end());
  state->mocap.clear();
  for (int b = 0; b < world.num_bodies(); ++b) {
    if (world.body(b).is_mocap) state->mocap.emplace_back(b, world.body_state(b).X_WB);
  }
}

struct SceneRenderer::Impl {
  internal::ModelPtr model;
  internal::DataPtr data;
  mjvScene scene;
  mjvOption option;
  mjvCamera camera;
  mjvPerturb perturb;
  mjrContext context;
  OrbitCamera orbit;

  void OrbitToMujoco() {
    for (int i = 0; i < 3; ++i) camera.lookat[i] = orbit.lookat[i];
    camera.distance = orbit.distance;
    camera.azimuth = orbit.azimuth_deg;
    camera.elevation = orbit.elevation_deg;
  }

  void MujocoToOrbit() {
    orbit.lookat = Vec3(camera.lookat[0], camera.lookat[1], camera.lookat[2]);
    orbit.distance = camera.distance;
    orbit.azimuth_deg = camera.azimuth;
    orbit.elevation_deg = camera.elevation;
  }

  // The slot for one more debug geom, initialized as decoration, or null when the scene is full.
  // `size`: a model geom's size parameters (geom_size), which mjv_initGeom turns into the
  // renderer's xyz scales (a sphere's radius into all three); null for scales set afterwards.
  mjvGeom* NewGeom(int type, const Rgba& color, const mjtNum* size = nullptr) {
    if (scene.ngeom >= scene.maxgeom) return nullptr;
    mjvGeom* g = &scene.geoms[scene.ngeom];
    const float rgba[4] = {color.r, color.g, color.b, color.a};
    mjv_initGeom(g, type, size, nullptr, nullptr, rgba);
    g->category = mjCAT_DECOR;
    g->objtype = mjOBJ_UNKNOWN;
    g->objid = -1;
    g->segid = scene.ngeom;
    g->transparent = color.a < 1.0f ? 1 : 0;
    ++scene.ngeom;
    return g;
  }

  void Forward() {
    mj_kinematics(model.get(), data.get());
    mj_comPos(model.get(), data.get());
    mj_camlight(model.get(), data.get());
    OrbitToMujoco();
    mjv_updateScene(model.get(), data.get(), &option, &perturb, &camera, mjCAT_ALL, &scene);
  }
};

SceneRenderer::SceneRenderer(const std::filesystem::path& mjcf,
                             const SceneRendererSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  std::array<char, 1000> error{};
  impl_->model.reset(
      mj_loadXML(mjcf.c_str(), nullptr, error.data(), static_cast<int>(error.size())));
  if (!impl_->model) {
    throw SceneError(mjcf.string() + ": cannot load the scene for drawing: " + error.data() +
                     "; check that `mrh validate` accepts the session");
  }
  impl_->data.reset(mj_makeData(impl_->model.get()));
  mjv_defaultScene(&impl_->scene);
  mjv_defaultOption(&impl_->option);
  mjv_defaultCamera(&impl_->camera);
  mjv_defaultPerturb(&impl_->perturb);
  mjr_defaultContext(&impl_->context);
  mjv_makeScene(impl_->model.get(), &impl_->scene, settings.max_geoms);
  mjr_makeContext(impl_->model.get(), &impl_->context, NearestFontScale(settings.font_scale));
  ResetCamera();
  impl_->Forward();
}

SceneRenderer::~SceneRenderer() {
  mjr_freeContext(&impl_->context);
  mjv_freeScene(&impl_->scene);
}

OrbitCamera& SceneRenderer::camera() {
  return impl_->orbit;
}

void SceneRenderer::ResetCamera() {
  mjv_defaultFreeCamera(impl_->model.get(), &impl_->camera);
  impl_->MujocoToOrbit();
}

void SceneRenderer::FrameBodies(const std::vector<int>& bodies) {
  const mjModel& m = *impl_->model;
  const mjData& d = *impl_->data;
  // Bounding box of the geoms' bounding spheres, then the sphere around that box's centre.
  Vec3 lo = Vec3::Constant(mjMAXVAL), hi = Vec3::Constant(-mjMAXVAL);
  std::vector<int> geoms;
  for (int g = 0; g < m.ngeom; ++g) {
    if (m.geom_type[g] == mjGEOM_PLANE) continue;
    if (std::find(bodies.begin(), bodies.end(), m.geom_bodyid[g]) == bodies.end()) continue;
    const Vec3 c(d.geom_xpos[3 * g], d.geom_xpos[3 * g + 1], d.geom_xpos[3 * g + 2]);
    lo = lo.cwiseMin(c - Vec3::Constant(m.geom_rbound[g]));
    hi = hi.cwiseMax(c + Vec3::Constant(m.geom_rbound[g]));
    geoms.push_back(g);
  }
  if (geoms.empty()) return;
  const Vec3 center = 0.5 * (lo + hi);
  double radius = 0.0;
  for (int g : geoms) {
    const Vec3 c(d.geom_xpos[3 * g], d.geom_xpos[3 * g + 1], d.geom_xpos[3 * g + 2]);
    radius = std::max(radius, (c - center).norm() + m.geom_rbound[g]);
  }
  const double half_fovy = 0.5 * m.vis.global.fovy * mjPI / 180.0;
  impl_->orbit.lookat = center;
  impl_->orbit.distance = kFrameMargin * radius / std::sin(half_fovy);
}

void SceneRenderer::MoveCamera(CameraMotion motion, double dx, double dy) {
  impl_->OrbitToMujoco();
  mjv_moveCamera(impl_->model.get(), ToMujoco(motion), dx, dy, &impl_->camera);
  impl_->MujocoToOrbit();
}

CameraFrame SceneRenderer::camera_frame() const {
  mjtNum head[3], forward[3], up[3];
  mjv_cameraInModel(head, forward, up, &impl_->scene);
  CameraFrame frame;
  frame.p_WC = Vec3(head[0], head[1], head[2]);
  frame.forward_W = Vec3(forward[0], forward[1], forward[2]).normalized();
  // Re-orthogonalize: the average of two GL cameras is orthogonal only up to rounding.
  const Vec3 up_W(up[0], up[1], up[2]);
  frame.up_W = (up_W - up_W.dot(frame.forward_W) * frame.forward_W).normalized();
  frame.frustum_height = mjv_frustumHeight(&impl_->scene);
  return frame;
}

void SceneRenderer::Update(const SceneState& state) {
  const mjModel& m = *impl_->model;
  mjData& d = *impl_->data;
  if (state.qpos.size() == static_cast<std::size_t>(m.nq)) {
    std::copy(state.qpos.begin(), state.qpos.end(), d.qpos);
    d.time = state.t;
  }
  for (const auto& [body, X_WB] : state.mocap) {
    if (body < 0 || body >= m.nbody || m.body_mocapid[body] < 0) continue;
    const int id = m.body_mocapid[body];
    for (int i = 0; i < 3; ++i) d.mocap_pos[3 * id + i] = X_WB.p[i];
    const Quat q = X_WB.q.normalized();
    const double wxyz[4] = {q.w(), q.x(), q.y(), q.z()};
    std::memcpy(d.mocap_quat + 4 * id, wxyz, sizeof(wxyz));
  }
  impl_->Forward();
}

bool SceneRenderer::AddArrow(const Vec3& from_W, const Vec3& to_W, double width,
                             const Rgba& color) {
  if ((to_W - from_W).norm() < kMinArrowLength) return true;
  mjvGeom* g = impl_->NewGeom(mjGEOM_ARROW, color);
  if (g == nullptr) return false;
  const mjtNum from[3] = {from_W.x(), from_W.y(), from_W.z()};
  const mjtNum to[3] = {to_W.x(), to_W.y(), to_W.z()};
  mjv_connector(g, mjGEOM_ARROW, width, from, to);
  return true;
}

bool SceneRenderer::AddSphere(const Vec3& p_W, double radius, const Rgba& color) {
  mjvGeom* g = impl_->NewGeom(mjGEOM_SPHERE, color);
  if (g == nullptr) return false;
  for (float& s : g->size) s = static_cast<float>(radius);
  SetPose(g, p_W, Mat3::Identity());
  return true;
}

bool SceneRenderer::AddPlane(const Vec3& p_W, const Vec3& n_W, double half_size,
                             const Rgba& color) {
  mjvGeom* g = impl_->NewGeom(mjGEOM_BOX, color);
  if (g == nullptr) return false;
  g->size[0] = g->size[1] = static_cast<float>(half_size);
  g->size[2] = static_cast<float>(kPlaneThicknessRatio * half_size);
  const Mat3 R = Quat::FromTwoVectors(Vec3::UnitZ(), n_W.normalized()).toRotationMatrix();
  SetPose(g, p_W, R);
  return true;
}

bool SceneRenderer::AddBodyGhost(int body, const Pose& X_WB, const Rgba& color) {
  const mjModel& m = *impl_->model;
  if (body < 0 || body >= m.nbody) return false;
  for (int id = 0; id < m.ngeom; ++id) {
    if (m.geom_bodyid[id] != body || m.geom_type[id] == mjGEOM_PLANE) continue;
    // Copying geom_size as the scales would flatten spheres and capsules (size[1..2] = 0).
    mjvGeom* g = impl_->NewGeom(m.geom_type[id], color, m.geom_size + 3 * id);
    if (g == nullptr) return false;
    g->dataid = m.geom_dataid[id];
    const Pose X_BG{Vec3(m.geom_pos[3 * id], m.geom_pos[3 * id + 1], m.geom_pos[3 * id + 2]),
                    Quat(m.geom_quat[4 * id], m.geom_quat[4 * id + 1], m.geom_quat[4 * id + 2],
                         m.geom_quat[4 * id + 3])};
    const Pose X_WG = X_WB * X_BG;
    SetPose(g, X_WG.p, X_WG.q.normalized().toRotationMatrix());
  }
  return true;
}

void SceneRenderer::Render(int width, int height) {
  mjr_setBuffer(mjFB_WINDOW, &impl_->context);
  const mjrRect viewport{0, 0, width, height};
  mjr_render(viewport, &impl_->scene, &impl_->context);
}

std::vector<std::uint8_t> SceneRenderer::ReadPixels(int width, int height) const {
  const auto row = static_cast<std::size_t>(width) * 3;
  std::vector<std::uint8_t> rgb(row * static_cast<std::size_t>(height));
  mjr_readPixels(rgb.data(), nullptr, mjrRect{0, 0, width, height}, &impl_->context);
  // OpenGL returns the bottom row first; images are stored top row first.
  std::vector<std::uint8_t> flipped(rgb.size());
  for (std::size_t y = 0; y < static_cast<std::size_t>(height); ++y) {
    std::memcpy(flipped.data() + y * row, rgb.data() + (rgb.size() - (y + 1) * row), row);
  }
  return flipped;
}

}  // namespace mrh::world
