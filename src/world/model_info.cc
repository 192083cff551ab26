// SPDX-License-Identifier: Apache-2.0
// Engine-neutral descriptions of a MuJoCo model's bodies and geoms (mass, inertia, shapes).
#include <mujoco/mujoco.h>

#include <memory>
#include <string>
#include <vector>

#include "mrh/core/error.h"
#include "world/world_impl.h"

namespace mrh::world::internal {
namespace {

std::string NameOf(const mjModel& m, mjtObj type, int id) {
  const char* name = mj_id2name(&m, type, id);
  return name ? std::string(name) : std::string();
}

// MuJoCo keeps the convex hull it collides with in mesh_graph: [numvert, numface,
// vert_edgeadr[numvert], vert_globalid[numvert], edge_localid[numvert + 3 numface],
// face_globalid[3 numface]]. Vertices are in the mesh frame, which the compiler made the geom
// frame.
std::shared_ptr<const geometry::ConvexMesh> ConvexHullOf(const mjModel& m, int mesh) {
  auto out = std::make_shared<geometry::ConvexMesh>();
  const float* vert = m.mesh_vert + 3 * m.mesh_vertadr[mesh];
  const auto vertex = [vert](int i) {
    return Vec3(static_cast<double>(vert[3 * i]), static_cast<double>(vert[3 * i + 1]),
                static_cast<double>(vert[3 * i + 2]));
  };
  if (m.mesh_graphadr[mesh] < 0) {
    // No hull was computed: the mesh itself is taken as convex.
    for (int i = 0; i < m.mesh_vertnum[mesh]; ++i) out->vertices.push_back(vertex(i));
    const int* face = m.mesh_face + 3 * m.mesh_faceadr[mesh];
    for (int f = 0; f < m.mesh_facenum[mesh]; ++f) {
      out->triangles.push_back({face[3 * f], face[3 * f + 1], face[3 * f + 2]});
    }
    return out;
  }
  const int* graph = m.mesh_graph + m.mesh_graphadr[mesh];
  const int num_vert = graph[0];
  const int num_face = graph[1];
  const int* global_id = graph + 2 + num_vert;
  const int* face = graph + 2 + 3 * num_vert + 3 * num_face;
  // Keep only the hull's vertices, renumbered.
  std::vector<int> local(static_cast<std::size_t>(m.mesh_vertnum[mesh]), -1);
  for (int i = 0; i < num_vert; ++i) {
    local[static_cast<std::size_t>(global_id[i])] = i;
    out->vertices.push_back(vertex(global_id[i]));
  }
  const auto renumber = [&local](int g) {
    return local[static_cast<std::size_t>(g)];
  };
  for (int f = 0; f < num_face; ++f) {
    out->triangles.push_back(
        {renumber(face[3 * f]), renumber(face[3 * f + 1]), renumber(face[3 * f + 2])});
  }
  return out;
}

// The shape type of a primitive MuJoCo geom type; false for meshes and height fields.
bool PrimitiveType(int type, geometry::ShapeType* out) {
  switch (type) {
    case mjGEOM_PLANE:
      *out = geometry::ShapeType::kPlane;
      return true;
    case mjGEOM_SPHERE:
      *out = geometry::ShapeType::kSphere;
      return true;
    case mjGEOM_CAPSULE:
      *out = geometry::ShapeType::kCapsule;
      return true;
    case mjGEOM_ELLIPSOID:
      *out = geometry::ShapeType::kEllipsoid;
      return true;
    case mjGEOM_CYLINDER:
      *out = geometry::ShapeType::kCylinder;
      return true;
    case mjGEOM_BOX:
      *out = geometry::ShapeType::kBox;
      return true;
    default:
      return false;
  }
}

[[noreturn]] void ThrowHeightField(const mjModel& m, int g, const std::string& origin) {
  throw SceneError(origin + ": geom " + Describe(m, mjOBJ_GEOM, g) + " of body " +
                   Describe(m, mjOBJ_BODY, m.geom_bodyid[g]) +
                   " is a height field; expected plane, sphere, capsule, ellipsoid, "
                   "cylinder, box or mesh geoms: replace it, e.g. by boxes or a plane");
}

geometry::Shape ShapeOf(const mjModel& m, int g, const std::string& origin,
                        std::vector<std::shared_ptr<const geometry::ConvexMesh>>* meshes) {
  geometry::Shape shape;
  shape.size = ToVec3(m.geom_size + 3 * g);
  if (!PrimitiveType(m.geom_type[g], &shape.type)) {
    if (m.geom_type[g] != mjGEOM_MESH) ThrowHeightField(m, g, origin);
    shape.type = geometry::ShapeType::kMesh;
    const auto mesh = static_cast<std::size_t>(m.geom_dataid[g]);
    if (!(*meshes)[mesh]) (*meshes)[mesh] = ConvexHullOf(m, m.geom_dataid[g]);
    shape.mesh = (*meshes)[mesh];
  }
  // Sizes mean nothing for planes (infinite) and meshes (their vertices carry the size).
  if (shape.type == geometry::ShapeType::kPlane || shape.type == geometry::ShapeType::kMesh) {
    shape.size = Vec3::Zero();
  }
  return shape;
}

BodyInfo DescribeBody(const mjModel& m, int b) {
  BodyInfo info;
  info.id = b;
  info.name = NameOf(m, mjOBJ_BODY, b);
  info.mass = m.body_mass[b];
  // MuJoCo stores the principal moments in the inertial frame, rotated by body_iquat from the
  // body frame: I_B = R diag(I) R^T.
  const Mat3 R = ToQuat(m.body_iquat + 4 * b).toRotationMatrix();
  info.inertia_B = R * ToVec3(m.body_inertia + 3 * b).asDiagonal() * R.transpose();
  info.p_BCm = ToVec3(m.body_ipos + 3 * b);
  info.is_mocap = m.body_mocapid[b] >= 0;
  info.is_static = HasNoDofs(m, b);
  info.parent = b > 0 ? m.body_parentid[b] : -1;
  info.free = m.body_jntnum[b] == 1 && m.jnt_type[m.body_jntadr[b]] == mjJNT_FREE;
  info.inv_weight = m.body_invweight0[2 * b];
  for (int g = 0; g < m.body_geomnum[b]; ++g) info.geoms.push_back(m.body_geomadr[b] + g);
  return info;
}

}  // namespace

void DescribeModel(const mjModel& m, const std::string& origin, std::vector<BodyInfo>* bodies,
                   std::vector<GeomInfo>* geoms) {
  bodies->clear();
  for (int b = 0; b < m.nbody; ++b) bodies->push_back(DescribeBody(m, b));
  // One ConvexMesh per MuJoCo mesh, shared by the geoms that use it.
  std::vector<std::shared_ptr<const geometry::ConvexMesh>> meshes(
      static_cast<std::size_t>(m.nmesh));
  geoms->clear();
  for (int g = 0; g < m.ngeom; ++g) {
    GeomInfo info;
    info.id = g;
    info.body = m.geom_bodyid[g];
    info.name = NameOf(m, mjOBJ_GEOM, g);
    info.shape = ShapeOf(m, g, origin, &meshes);
    info.X_BG = Pose{ToVec3(m.geom_pos + 3 * g), ToQuat(m.geom_quat + 4 * g)};
    info.collides = (m.geom_contype[g] | m.geom_conaffinity[g]) != 0;
    if (m.geom_matid[g] >= 0) info.material = NameOf(m, mjOBJ_MATERIAL, m.geom_matid[g]);
    geoms->push_back(std::move(info));
  }
}

std::string Describe(const mjModel& m, mjtObj type, int id) {
  const std::string name = NameOf(m, type, id);
  return name.empty() ? "#" + std::to_string(id) : "'" + name + "'";
}

}  // namespace mrh::world::internal
