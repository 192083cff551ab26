// SPDX-License-Identifier: Apache-2.0
// Export of the contact local model: island growth through MuJoCo's contacts and the
// contact rows in body-fixed terms.
#include "mrh/world/contact_export.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "mrh/core/error.h"
#include "mrh/ir/snapshot.h"
#include "world/contact_manifold.h"
#include "world/world_impl.h"

namespace mrh::world {
namespace {

using internal::ToVec3;

// Added to the bounding-sphere reach of the island-restricted pass (m): roundoff only.
constexpr double kNearSlack = 1e-6;

}  // namespace

ContactExporter::ContactExporter(World* world, double margin, bool whole_world, bool articulated)
    : world_(world), margin_(margin), whole_world_(whole_world), articulated_(articulated) {
  if (!(margin >= 0.0)) throw InvalidArgument("contact export margin must be >= 0");
  saved_margin_.resize(static_cast<std::size_t>(world->num_geoms()));
  margins_.resize(static_cast<std::size_t>(world->num_geoms()));
  saved_filter_.resize(2 * static_cast<std::size_t>(world->num_geoms()));
  saved_body_margin_.resize(static_cast<std::size_t>(world->num_bodies()));
  local_index_.assign(static_cast<std::size_t>(world->num_bodies()), -1);
  near_.assign(static_cast<std::size_t>(world->num_bodies()), 0);
  near_bodies_.reserve(static_cast<std::size_t>(world->num_bodies()));
  mechanism_.assign(static_cast<std::size_t>(world->num_bodies()), 0);
  if (articulated_) ClassifyBodies();
}

bool ContactExporter::IsIslandBody(int body) const {
  return IsFreeBody(body) || (body > 0 && mechanism_[static_cast<std::size_t>(body)] != 0);
}

bool ContactExporter::IsFreeBody(int body) const {
  const mjModel& m = *world_->impl_->model;
  if (body <= 0 || m.body_jntnum[body] != 1 || m.body_mocapid[body] >= 0) return false;
  return m.jnt_type[m.body_jntadr[body]] == mjJNT_FREE;
}

// The margin of geom g: margin_, or the distance any of its points may travel over the rows'
// horizon (two physics steps: rows found at the start state of step k are used in the haptic
// period after it) if that is larger. A box tipping over at 10 rad/s moves its landing face's
// corners 3 cm in 40 ms: with a fixed 5 mm margin that face would have no rows when it lands,
// fall 1 cm into the floor and be thrown out. Speed bound: |v_origin| + |ω| (|offset| + rbound).
double ContactExporter::GeomMargin(int g) const {
  const World::Impl& w = *world_->impl_;
  const mjModel& m = *w.model;
  const mjData& d = *w.data;
  const int body = m.geom_bodyid[g];
  double margin = std::max(m.geom_margin[g], margin_);
  if (mechanism_[static_cast<std::size_t>(body)] != 0) return JointedMargin(g, margin);
  if (!IsFreeBody(body)) return margin;
  const mjtNum* qvel = d.qvel + m.jnt_dofadr[m.body_jntadr[body]];
  const double v = std::sqrt(qvel[0] * qvel[0] + qvel[1] * qvel[1] + qvel[2] * qvel[2]);
  const double omega = std::sqrt(qvel[3] * qvel[3] + qvel[4] * qvel[4] + qvel[5] * qvel[5]);
  const mjtNum* gp = d.geom_xpos + 3 * g;
  const mjtNum* bp = d.xpos + 3 * body;
  const double offset =
      std::sqrt((gp[0] - bp[0]) * (gp[0] - bp[0]) + (gp[1] - bp[1]) * (gp[1] - bp[1]) +
                (gp[2] - bp[2]) * (gp[2] - bp[2]));
  const double horizon = 2.0 * m.opt.timestep;
  return std::max(margin, horizon * (v + omega * (offset + m.geom_rbound[g])));
}

// Collision detection at the current positions with every geom's margin raised (GeomMargin).
void ContactExporter::Collide(bool refresh_kinematics) {
  World::Impl& w = *world_->impl_;
  mjModel* m = w.model.get();
  w.kinematics_stale = w.kinematics_stale || refresh_kinematics;
  w.EnsureKinematics();
  for (int g = 0; g < m->ngeom; ++g) {
    saved_margin_[static_cast<std::size_t>(g)] = m->geom_margin[g];
    margins_[static_cast<std::size_t>(g)] = GeomMargin(g);
  }
  for (int g = 0; g < m->ngeom; ++g) m->geom_margin[g] = margins_[static_cast<std::size_t>(g)];
  // MuJoCo's broadphase bounds each body by body_margin (the largest geom margin + gap, set when
  // the model is compiled): raise it with the geoms' margins, or pairs within the raised margins
  // are never tested.
  std::copy_n(m->body_margin, m->nbody, saved_body_margin_.begin());
  for (int g = 0; g < m->ngeom; ++g) {
    mjtNum& bound = m->body_margin[m->geom_bodyid[g]];
    bound = std::max(bound, m->geom_margin[g] + m->geom_gap[g]);
  }
  if (!whole_world_) DisableFarGeoms();
  {
    const internal::MujocoScope scope(w.origin);  // MuJoCo's errors name the scene
    mj_collision(m, w.data.get());
  }
  if (!whole_world_) RestoreFilters();
  for (int g = 0; g < m->ngeom; ++g) m->geom_margin[g] = saved_margin_[static_cast<std::size_t>(g)];
  std::copy_n(saved_body_margin_.begin(), m->nbody, m->body_margin);
}

// True if geoms g and h may touch: the bounding-sphere test of MuJoCo's mj_collideGeoms (centre
// distance <= both rbounds + the larger margin) with the margins as raised for this export,
// plus a slack; unbounded geoms (planes, rbound 0) always may.
bool ContactExporter::Reaches(int g, int h) const {
  const mjModel& m = *world_->impl_->model;
  const mjData& d = *world_->impl_->data;
  if (m.geom_rbound[g] <= 0.0 || m.geom_rbound[h] <= 0.0) return true;
  const double reach = m.geom_rbound[g] + m.geom_rbound[h] +
                       std::max(m.geom_margin[g], m.geom_margin[h]) + kNearSlack;
  return (ToVec3(d.geom_xpos + 3 * g) - ToVec3(d.geom_xpos + 3 * h)).norm() <= reach;
}

// True if geom g may touch a geom of a near_ body (or belongs to one).
bool ContactExporter::NearIsland(int g) const {
  const mjModel& m = *world_->impl_->model;
  if (near_[static_cast<std::size_t>(m.geom_bodyid[g])]) return true;
  for (const int body : near_bodies_) {
    for (int h = m.body_geomadr[body]; h < m.body_geomadr[body] + m.body_geomnum[body]; ++h) {
      if (Reaches(g, h)) return true;
    }
  }
  return false;
}

// Adds to near_ every free body that may touch a near_ body, transitively: the island cannot
// reach beyond them, so one collision pass finds all its contacts.
void ContactExporter::CloseNear() {
  const mjModel& m = *world_->impl_->model;
  for (std::size_t i = 0; i < near_bodies_.size(); ++i) {
    const int body = near_bodies_[i];
    for (int other = 1; other < m.nbody; ++other) {
      if (near_[static_cast<std::size_t>(other)] || !IsIslandBody(other)) continue;
      bool reaches = false;
      for (int g = m.body_geomadr[body]; g < m.body_geomadr[body] + m.body_geomnum[body]; ++g) {
        for (int h = m.body_geomadr[other]; h < m.body_geomadr[other] + m.body_geomnum[other];
             ++h) {
          reaches = reaches || Reaches(g, h);
        }
      }
      if (reaches) AddNear(other);
    }
  }
}

// Every geom that cannot touch a near_ body leaves the collision pass (contype and conaffinity
// 0 for the call): MuJoCo's broadphase skips it, and the pairs it would have made give no
// contact of the island anyway, so the island's contacts are those of a whole-world pass.
void ContactExporter::DisableFarGeoms() {
  mjModel* m = world_->impl_->model.get();
  CloseNear();
  for (int g = 0; g < m->ngeom; ++g) {
    saved_filter_[2 * static_cast<std::size_t>(g)] = m->geom_contype[g];
    saved_filter_[2 * static_cast<std::size_t>(g) + 1] = m->geom_conaffinity[g];
    if (!NearIsland(g)) m->geom_contype[g] = m->geom_conaffinity[g] = 0;
  }
}

void ContactExporter::RestoreFilters() {
  mjModel* m = world_->impl_->model.get();
  for (int g = 0; g < m->ngeom; ++g) {
    m->geom_contype[g] = saved_filter_[2 * static_cast<std::size_t>(g)];
    m->geom_conaffinity[g] = saved_filter_[2 * static_cast<std::size_t>(g) + 1];
  }
}

bool ContactExporter::AddOne(int body, int motion, ir::LocalContactModel* out) {
  const int index = local_index_[static_cast<std::size_t>(body)];
  if (index >= 0) {
    ir::LocalIslandBody& b = out->bodies[static_cast<std::size_t>(index)];
    if (b.motion < 0) b.motion = motion;
    return true;
  }
  const BodyInfo& info = world_->body(body);
  const BodyState state = world_->body_state(body);
  ir::LocalIslandBody b;
  b.body = body;
  b.motion = motion;
  b.mass = info.mass;
  b.inertia_B = info.inertia_B;
  b.inv_weight = info.free ? 0.0 : info.inv_weight;
  b.X_WB = state.X_WB;
  b.p_BCm = info.p_BCm;
  b.V_WCm = state.V_WCm;
  if (!out->bodies.PushBack(b)) return false;
  local_index_[static_cast<std::size_t>(body)] = static_cast<int>(out->bodies.size()) - 1;
  return true;
}

// Adds every free body touching an island body until nothing changes (or the capacity is full).
std::uint32_t ContactExporter::GrowIsland(ir::LocalContactModel* out) {
  const World::Impl& w = *world_->impl_;
  const mjModel& m = *w.model;
  const mjData& d = *w.data;
  bool grew = true;
  while (grew) {
    grew = false;
    for (int c = 0; c < d.ncon; ++c) {
      const int b1 = m.geom_bodyid[d.contact[c].geom1];
      const int b2 = m.geom_bodyid[d.contact[c].geom2];
      const bool in1 = local_index_[static_cast<std::size_t>(b1)] >= 0;
      const bool in2 = local_index_[static_cast<std::size_t>(b2)] >= 0;
      if (in1 == in2) continue;
      const int other = in1 ? b2 : b1;
      if (!IsIslandBody(other)) continue;
      if (!AddBody(other, -1, out)) return ir::kStatusBodiesFull;
      grew = true;
    }
  }
  return ir::kStatusOk;
}

std::uint32_t ContactExporter::Export(std::span<const int> seeds, std::span<const int> motions,
                                      ir::LocalContactModel* out) {
  out->valid = true;
  out->bodies.Clear();
  out->contacts.Clear();
  out->gravity = world_->gravity();
  SetNear(seeds);
  std::uint32_t status = ir::kStatusOk;
  // Collide around the bodies the seeds may reach (CloseNear); repeated, as a safeguard, until
  // the island has no body whose neighbourhood was left out (one pass with whole_world_).
  for (bool first = true;; first = false) {
    Collide(first);
    ClearIsland(out);
    status = ir::kStatusOk;
    for (std::size_t i = 0; i < seeds.size(); ++i) {
      if (!IsIslandBody(seeds[i])) continue;
      if (!AddBody(seeds[i], motions[i], out)) status |= ir::kStatusBodiesFull;
    }
    status |= GrowIsland(out);
    bool covered = true;
    for (const ir::LocalIslandBody& b : out->bodies) {
      covered = covered && near_[static_cast<std::size_t>(b.body)] != 0;
    }
    if (whole_world_ || covered) break;
    for (const ir::LocalIslandBody& b : out->bodies) AddNear(b.body);
  }
  status |= AddRows(out);
  out->joints.Clear();
  if (articulated_) status |= AddJoints(out);
  for (const ir::LocalIslandBody& b : out->bodies) {
    local_index_[static_cast<std::size_t>(b.body)] = -1;
  }
  for (const int body : near_bodies_) near_[static_cast<std::size_t>(body)] = 0;
  near_bodies_.clear();
  return status;
}

void ContactExporter::SetNear(std::span<const int> seeds) {
  for (const int body : seeds) {
    if (IsIslandBody(body)) AddNear(body);
  }
}

void ContactExporter::AddNear(int body) {
  if (near_[static_cast<std::size_t>(body)]) return;
  near_[static_cast<std::size_t>(body)] = 1;
  near_bodies_.push_back(body);
}

// Forgets the island's bodies (local_index_) and empties the model.
void ContactExporter::ClearIsland(ir::LocalContactModel* out) {
  island_joints_ = 0;
  for (const ir::LocalIslandBody& b : out->bodies) {
    local_index_[static_cast<std::size_t>(b.body)] = -1;
  }
  out->bodies.Clear();
  out->contacts.Clear();
}

}  // namespace mrh::world
