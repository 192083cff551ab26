// SPDX-License-Identifier: Apache-2.0
// The contact local model's rows: each MuJoCo contact with an island body in body-fixed terms,
// with the round cores and ellipsoids the local solve re-derives contact points from.
#include <mujoco/mujoco.h>

#include <algorithm>

#include "mrh/ir/snapshot.h"
#include "mrh/world/contact_export.h"
#include "world/contact_manifold.h"
#include "world/world_impl.h"

namespace mrh::world {
namespace {

using internal::ToVec3;

// The contact's distance, friction (coefficient and the scene's cone) and soft-constraint
// parameters into its row.
void SetContactParameters(const mjModel& m, const mjContact& con, ir::LocalContactRow* row) {
  row->dist0 = con.dist;
  row->mu = con.dim >= 3 ? con.friction[0] : 0.0;
  row->pyramidal = m.opt.cone == mjCONE_PYRAMIDAL;
  for (int i = 0; i < 2; ++i) row->solref[i] = con.solref[i];
  for (int i = 0; i < 5; ++i) row->solimp[i] = con.solimp[i];
}

// The core of a round geom g (sphere, capsule) nearest the world point p, and its radius; 0 for
// any other shape.
double RoundCore(const mjModel& m, const mjData& d, int g, const Vec3& p, Vec3* core) {
  const Vec3 c = ToVec3(d.geom_xpos + 3 * g);
  if (m.geom_type[g] == mjGEOM_SPHERE) {
    *core = c;
    return m.geom_size[3 * g];
  }
  if (m.geom_type[g] == mjGEOM_CAPSULE) {
    const mjtNum* R = d.geom_xmat + 9 * g;
    const Vec3 axis(R[2], R[5], R[8]);
    const double h = m.geom_size[3 * g + 1];
    *core = c + std::clamp(axis.dot(p - c), -h, h) * axis;
    return m.geom_size[3 * g];
  }
  return 0.0;
}

// A geom whose contact point the local solve re-derives each tick (sphere, capsule, ellipsoid).
bool IsRound(const mjModel& m, int g) {
  const int type = m.geom_type[g];
  return type == mjGEOM_SPHERE || type == mjGEOM_CAPSULE || type == mjGEOM_ELLIPSOID;
}

// An ellipsoid geom g: its centre, semi-axes and world orientation; false for any other shape.
bool Ellipsoid(const mjModel& m, const mjData& d, int g, Vec3* centre, Vec3* axes, Quat* q_WG) {
  if (m.geom_type[g] != mjGEOM_ELLIPSOID) return false;
  *centre = ToVec3(d.geom_xpos + 3 * g);
  *axes = ToVec3(m.geom_size + 3 * g);
  mjtNum q[4];
  mju_mat2Quat(q, d.geom_xmat + 9 * g);
  *q_WG = Quat(q[0], q[1], q[2], q[3]);
  return true;
}

// A contact's two sides as the row orders them: A the island body (see AddRows), B the other.
struct Sides {
  bool a_is_2;
  int gA, gB;   // geoms
  Vec3 pA, pB;  // points on their surfaces, world
  Vec3 n;       // B → A, world
  Vec3 t;       // a tangent, world
};

Sides SidesOf(const mjModel& m, const mjContact& con, int i1, int i2) {
  Sides s;
  const Vec3 n12 = ToVec3(con.frame);  // geom1 → geom2
  const Vec3 pos = ToVec3(con.pos);
  const Vec3 p1 = pos - 0.5 * con.dist * n12;
  const Vec3 p2 = pos + 0.5 * con.dist * n12;
  s.a_is_2 = i2 >= 0 && !(i1 >= 0 && IsRound(m, con.geom1) && !IsRound(m, con.geom2));
  s.pA = s.a_is_2 ? p2 : p1;
  s.pB = s.a_is_2 ? p1 : p2;
  s.n = s.a_is_2 ? n12 : Vec3(-n12);
  s.t = ToVec3(con.frame + 3);  // the sign of a tangent does not change the set
  s.gA = s.a_is_2 ? con.geom2 : con.geom1;
  s.gB = s.a_is_2 ? con.geom1 : con.geom2;
  return s;
}

// The row's points in their bodies' frames and its normal and tangent in B's (world for a
// static B); row->a and row->b set.
void SetFrames(const Sides& s, const ir::LocalContactModel& out, ir::LocalContactRow* row) {
  const Pose& X_WA = out.bodies[static_cast<std::size_t>(row->a)].X_WB;
  row->p_A = X_WA.Inverse() * s.pA;
  if (row->b >= 0) {
    const Pose& X_WB = out.bodies[static_cast<std::size_t>(row->b)].X_WB;
    row->p_B = X_WB.Inverse() * s.pB;
    row->n_B = X_WB.q.conjugate() * s.n;
    row->t_B = X_WB.q.conjugate() * s.t;
  } else {
    row->p_B = s.pB;
    row->n_B = s.n;
    row->t_B = s.t;
  }
}

// A round core or an ellipsoid of each side's geom, in its body's frame (B's only if it moves).
void SetShapes(const mjModel& m, const mjData& d, const Sides& s, const ir::LocalContactModel& out,
               ir::LocalContactRow* row) {
  const Pose& X_WA = out.bodies[static_cast<std::size_t>(row->a)].X_WB;
  Vec3 core;
  if (const double r = RoundCore(m, d, s.gA, s.pA, &core); r > 0.0) {
    row->r_A = r;
    row->s_A = X_WA.Inverse() * core;
  }
  Vec3 axes;
  Quat q_WG;
  if (Ellipsoid(m, d, s.gA, &core, &axes, &q_WG)) {
    row->e_A = axes;
    row->s_A = X_WA.Inverse() * core;
    row->q_A = X_WA.q.conjugate() * q_WG;
  }
  if (row->b < 0) return;
  const Pose& X_WB = out.bodies[static_cast<std::size_t>(row->b)].X_WB;
  if (const double r = RoundCore(m, d, s.gB, s.pB, &core); r > 0.0) {
    row->r_B = r;
    row->s_B = X_WB.Inverse() * core;
  } else if (Ellipsoid(m, d, s.gB, &core, &axes, &q_WG)) {
    row->e_B = axes;
    row->s_B = X_WB.Inverse() * core;
    row->q_B = X_WB.q.conjugate() * q_WG;
  }
}

// MuJoCo emits a geom pair's contacts together: is contact c its pair's last?
bool LastOfPair(const mjData& d, int c) {
  const mjContact& con = d.contact[c];
  return c + 1 == d.ncon || d.contact[c + 1].geom1 != con.geom1 ||
         d.contact[c + 1].geom2 != con.geom2;
}

}  // namespace

// One row per contact with an island body: A is the island body (geom2's if both are, unless
// only geom1 is round: the normal of a round body against another shape must stay fixed on the
// other body, and B's normal is the one that follows B), the normal points from B to A, points on
// each surface in its own body frame (world for static B).
std::uint32_t ContactExporter::AddRows(ir::LocalContactModel* out) {
  const World::Impl& w = *world_->impl_;
  const mjModel& m = *w.model;
  const mjData& d = *w.data;
  for (int c = 0; c < d.ncon; ++c) {
    const mjContact& con = d.contact[c];
    const int i1 = local_index_[static_cast<std::size_t>(m.geom_bodyid[con.geom1])];
    const int i2 = local_index_[static_cast<std::size_t>(m.geom_bodyid[con.geom2])];
    if (i1 < 0 && i2 < 0) continue;
    const Sides s = SidesOf(m, con, i1, i2);
    ir::LocalContactRow row;
    row.a = s.a_is_2 ? i2 : i1;
    row.b = s.a_is_2 ? i1 : i2;  // i2 < 0: B is static
    SetFrames(s, *out, &row);
    SetContactParameters(m, con, &row);
    SetShapes(m, d, s, *out, &row);
    if (!out->contacts.PushBack(row)) return ir::kStatusContactsFull;
    // Complete the pair after its last contact, so that its rows stay consecutive and the
    // vertices MuJoCo's rows already hold are skipped.
    if (!LastOfPair(d, c) || row.r_A > 0.0 || row.e_A.x() > 0.0) continue;
    const Pose& X_WA = out->bodies[static_cast<std::size_t>(row.a)].X_WB;
    const Pose X_WB = row.b >= 0 ? out->bodies[static_cast<std::size_t>(row.b)].X_WB : Pose{};
    if (internal::AddVertexRows(m, d, s.gA, s.gB, row, X_WA, X_WB,
                                margins_[static_cast<std::size_t>(s.gA)], out) != ir::kStatusOk) {
      return ir::kStatusContactsFull;
    }
  }
  return ir::kStatusOk;
}

}  // namespace mrh::world
