// SPDX-License-Identifier: Apache-2.0
#include "contact_manifold.h"

#include <array>
#include <cmath>
#include <numbers>

namespace mrh::world::internal {
namespace {

constexpr double kSameRow = 1e-3;  // m, in A's frame
constexpr int kRimPoints = 8;      // per cylinder cap

bool HasVertices(const mjModel& m, int g) {
  const int type = m.geom_type[g];
  return type == mjGEOM_BOX || type == mjGEOM_MESH || type == mjGEOM_CYLINDER;
}

// A surface whose contact with a vertex is well described by the tangent plane of one contact.
bool FlatFaced(const mjModel& m, int g) {
  const int type = m.geom_type[g];
  return type == mjGEOM_PLANE || type == mjGEOM_BOX || type == mjGEOM_MESH ||
         type == mjGEOM_CYLINDER;
}

bool NearExistingRow(const ir::LocalContactModel& out, const ir::LocalContactRow& row,
                     const Vec3& p_A) {
  for (const ir::LocalContactRow& r : out.contacts) {
    if (r.a == row.a && r.b == row.b && (r.p_A - p_A).norm() < kSameRow) return true;
  }
  return false;
}

// Calls f(p_G) for each vertex of geom g in its geom frame.
template <typename F>
void ForEachVertex(const mjModel& m, int g, F&& f) {
  const mjtNum* s = m.geom_size + 3 * g;
  if (m.geom_type[g] == mjGEOM_BOX) {
    for (int i = 0; i < 8; ++i) {
      f(Vec3((i & 1 ? 1 : -1) * s[0], (i & 2 ? 1 : -1) * s[1], (i & 4 ? 1 : -1) * s[2]));
    }
  } else if (m.geom_type[g] == mjGEOM_CYLINDER) {
    for (int i = 0; i < 2 * kRimPoints; ++i) {
      const double a = 2.0 * std::numbers::pi * (i % kRimPoints) / kRimPoints;
      f(Vec3(s[0] * std::cos(a), s[0] * std::sin(a), (i < kRimPoints ? -1 : 1) * s[1]));
    }
  } else {
    const int mesh = m.geom_dataid[g];
    if (mesh < 0) return;
    const float* v = m.mesh_vert + 3 * m.mesh_vertadr[mesh];
    for (int i = 0; i < m.mesh_vertnum[mesh]; ++i) f(Vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]));
  }
}

}  // namespace

std::uint32_t AddVertexRows(const mjModel& m, const mjData& d, int geom_A, int geom_B,
                            const ir::LocalContactRow& row, const Pose& X_WA, const Pose& X_WB,
                            double margin, ir::LocalContactModel* out) {
  if (!HasVertices(m, geom_A) || !FlatFaced(m, geom_B)) return ir::kStatusOk;
  const bool static_B = row.b < 0;
  const Vec3 pB_W = static_B ? row.p_B : X_WB * row.p_B;
  const Vec3 n_W = static_B ? row.n_B : X_WB.q * row.n_B;
  const Vec3 x_G(d.geom_xpos[3 * geom_A], d.geom_xpos[3 * geom_A + 1], d.geom_xpos[3 * geom_A + 2]);
  const mjtNum* R = d.geom_xmat + 9 * geom_A;
  std::uint32_t status = ir::kStatusOk;
  ForEachVertex(m, geom_A, [&](const Vec3& v_G) {
    if (status != ir::kStatusOk) return;
    const Vec3 v_W = x_G + Vec3(R[0] * v_G.x() + R[1] * v_G.y() + R[2] * v_G.z(),
                                R[3] * v_G.x() + R[4] * v_G.y() + R[5] * v_G.z(),
                                R[6] * v_G.x() + R[7] * v_G.y() + R[8] * v_G.z());
    const double gap = n_W.dot(v_W - pB_W);
    if (!(gap < margin)) return;
    const Vec3 p_A = X_WA.Inverse() * v_W;
    if (NearExistingRow(*out, row, p_A)) return;
    ir::LocalContactRow v = row;
    v.p_A = p_A;
    const Vec3 on_B = v_W - gap * n_W;
    v.p_B = static_B ? on_B : X_WB.Inverse() * on_B;
    v.dist0 = gap;
    if (!out->contacts.PushBack(v)) status = ir::kStatusContactsFull;
  });
  return status;
}

}  // namespace mrh::world::internal
