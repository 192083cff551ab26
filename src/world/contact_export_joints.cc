// SPDX-License-Identifier: Apache-2.0
// The mechanisms of the contact local model: which kinematic trees the island can simulate,
// whole trees joining the island, and their joints exported as ir::LocalJoint.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "mrh/ir/snapshot.h"
#include "mrh/world/contact_export.h"
#include "world/world_impl.h"

namespace mrh::world {
namespace {

using internal::ToQuat;
using internal::ToVec3;

// True if a body of a moving tree has no degrees of freedom of its own (welded to its parent).
bool Moving(const mjModel& m, int body) {
  return m.body_weldid[body] != 0 && m.body_mocapid[body] < 0;
}

// Joint `jnt`'s type, frames on the child, coordinates and passive and limit terms.
void FillJoint(const mjModel& m, int jnt, ir::LocalJoint* out) {
  ir::LocalJoint& j = *out;
  const int q = m.jnt_qposadr[jnt], v = m.jnt_dofadr[jnt];
  j.joint = jnt;
  j.type = m.jnt_type[jnt] == mjJNT_HINGE   ? ir::LocalJointType::kHinge
           : m.jnt_type[jnt] == mjJNT_SLIDE ? ir::LocalJointType::kSlide
                                            : ir::LocalJointType::kBall;
  j.X_CJ = Pose{ToVec3(m.jnt_pos + 3 * jnt), Quat::Identity()};
  j.axis = ToVec3(m.jnt_axis + 3 * jnt).normalized();
  j.qpos0 = j.type == ir::LocalJointType::kBall ? 0.0 : m.qpos0[q];
  j.spring_ref = m.qpos_spring[q];
  if (j.type == ir::LocalJointType::kBall) j.spring_q = ToQuat(m.qpos_spring + q);
  j.stiffness = m.jnt_stiffness[jnt];
  j.damping = m.dof_damping[v];
  j.frictionloss = m.dof_frictionloss[v];
  j.armature = m.dof_armature[v];
  j.inv_weight = m.dof_invweight0[v];
  j.limited = m.jnt_limited[jnt] != 0;
  j.range[0] = m.jnt_range[2 * jnt];
  j.range[1] = m.jnt_range[2 * jnt + 1];
  j.margin = m.jnt_margin[jnt];
  std::copy_n(m.jnt_solref + mjNREF * jnt, 2, j.solref_limit);
  std::copy_n(m.jnt_solimp + mjNIMP * jnt, 5, j.solimp_limit);
  std::copy_n(m.dof_solref + mjNREF * v, 2, j.solref_friction);
  std::copy_n(m.dof_solimp + mjNIMP * v, 5, j.solimp_friction);
}

// True if `body`'s joints are two or three slides along orthogonal axes (a translating body:
// each coordinate is the displacement along its own axis).
bool OrthogonalSlides(const mjModel& m, int body) {
  const int first = m.body_jntadr[body];
  const int count = m.body_jntnum[body];
  if (count < 2 || count > 3) return false;
  for (int a = first; a < first + count; ++a) {
    if (m.jnt_type[a] != mjJNT_SLIDE) return false;
    for (int b = first; b < a; ++b) {
      const Vec3 u = ToVec3(m.jnt_axis + 3 * a).normalized();
      if (std::abs(u.dot(ToVec3(m.jnt_axis + 3 * b).normalized())) > 1e-9) return false;
    }
  }
  return true;
}

// The island joints body `body` needs: one per joint, one (a weld) for none.
int JointsOf(const mjModel& m, int body) {
  return std::max(1, static_cast<int>(m.body_jntnum[body]));
}

}  // namespace

// Why the local simulation cannot take moving body `body` ("" if it can): one hinge, slide or
// ball joint (a ball without limits), two or three orthogonal slides, or none on a moving parent,
// is what the island's joint rows model; a free body is simulated as before.
std::string ContactExporter::Unsupported(int body) const {
  const mjModel& m = *world_->impl_->model;
  const std::string name = internal::Describe(m, mjOBJ_BODY, body);
  const int parent = m.body_parentid[body];
  if (m.body_mocapid[parent] >= 0) {
    return "body " + name + ": its parent " + internal::Describe(m, mjOBJ_BODY, parent) +
           " is a mocap body";
  }
  if (m.body_jntnum[body] > 1 && !OrthogonalSlides(m, body)) {
    return "body " + name + ": " + std::to_string(m.body_jntnum[body]) + " joints (joint " +
           internal::Describe(m, mjOBJ_JOINT, m.body_jntadr[body]) +
           " and more); one joint per body, or up to three orthogonal slides, is simulated";
  }
  if (m.body_jntnum[body] == 0) return "";
  const int joint = m.body_jntadr[body];
  if (m.jnt_type[joint] == mjJNT_BALL && m.jnt_limited[joint]) {
    return "body " + name + ": ball joint " + internal::Describe(m, mjOBJ_JOINT, joint) +
           " has limits, which are not simulated locally";
  }
  return "";
}

// mechanism_: every moving, non-free body of a tree all of whose moving bodies are supported,
// and every such tree's free root; warnings_ names the bodies of the other trees.
void ContactExporter::ClassifyBodies() {
  const mjModel& m = *world_->impl_->model;
  std::vector<char> bad(static_cast<std::size_t>(m.nbody), 0);
  std::vector<char> jointed(static_cast<std::size_t>(m.nbody), 0);
  for (int b = 1; b < m.nbody; ++b) {
    if (!Moving(m, b) || IsFreeBody(b)) continue;
    const auto root = static_cast<std::size_t>(m.body_rootid[b]);
    jointed[root] = 1;
    const std::string why = Unsupported(b);
    if (why.empty()) continue;
    bad[root] = 1;
    warnings_.push_back(
        why + "; the world steps this mechanism and the local island treats it as static");
  }
  for (int b = 1; b < m.nbody; ++b) {
    const auto root = static_cast<std::size_t>(m.body_rootid[b]);
    if (Moving(m, b) && jointed[root] && !bad[root]) mechanism_[static_cast<std::size_t>(b)] = 1;
  }
}

// A mechanism body adds its whole tree (every moving body, parents first: MuJoCo numbers a
// parent before its children) or nothing if the tree does not fit; other bodies add themselves.
bool ContactExporter::AddBody(int body, int motion, ir::LocalContactModel* out) {
  if (mechanism_[static_cast<std::size_t>(body)] == 0) return AddOne(body, motion, out);
  const mjModel& m = *world_->impl_->model;
  const int root = m.body_rootid[body];
  std::size_t missing = 0, joints = 0;
  for (int b = root; b < m.nbody; ++b) {
    if (m.body_rootid[b] != root || mechanism_[static_cast<std::size_t>(b)] == 0 ||
        local_index_[static_cast<std::size_t>(b)] >= 0) {
      continue;
    }
    ++missing;
    if (!IsFreeBody(b)) joints += static_cast<std::size_t>(JointsOf(m, b));
  }
  // The whole tree with its joints, or nothing: a body without its joint rows would fly free.
  if (out->bodies.size() + missing > ir::kMaxLocalBodies ||
      island_joints_ + joints > ir::kMaxLocalJoints) {
    return false;
  }
  island_joints_ += joints;
  for (int b = root; b < m.nbody; ++b) {
    if (m.body_rootid[b] != root || mechanism_[static_cast<std::size_t>(b)] == 0) continue;
    if (!AddOne(b, b == body ? motion : -1, out)) return false;
  }
  return true;
}

// GeomMargin for a mechanism's geom: the distance its points may travel over the rows' horizon
// at the body's current COM twist.
double ContactExporter::JointedMargin(int g, double margin) const {
  const mjModel& m = *world_->impl_->model;
  const int body = m.geom_bodyid[g];
  const BodyState s = world_->body_state(body);
  const Vec3 offset = world_->geom_pose(g).p - s.p_WCm;
  const double horizon = 2.0 * m.opt.timestep;
  return std::max(
      margin, horizon * (s.V_WCm.v.norm() + s.V_WCm.w.norm() * (offset.norm() + m.geom_rbound[g])));
}

// The joint of every island body of a mechanism to its parent (an island body, or static).
std::uint32_t ContactExporter::AddJoints(ir::LocalContactModel* out) const {
  const mjModel& m = *world_->impl_->model;
  for (std::size_t i = 0; i < out->bodies.size(); ++i) {
    const int body = out->bodies[i].body;
    if (mechanism_[static_cast<std::size_t>(body)] == 0 || IsFreeBody(body)) continue;
    const int parent = m.body_parentid[body];
    ir::LocalJoint j;
    j.child = static_cast<int>(i);
    j.parent = local_index_[static_cast<std::size_t>(parent)];
    j.type = ir::LocalJointType::kWeld;
    const Pose X_PB{ToVec3(m.body_pos + 3 * body), ToQuat(m.body_quat + 4 * body)};
    for (int k = 0; k < JointsOf(m, body); ++k) {  // a translating body's slides: consecutive
      if (m.body_jntnum[body] > 0) FillJoint(m, m.body_jntadr[body] + k, &j);
      j.X_PJ = X_PB * j.X_CJ;
      if (j.parent < 0) j.X_PJ = world_->body_state(parent).X_WB * j.X_PJ;
      if (!out->joints.PushBack(j)) return ir::kStatusBodiesFull;
    }
  }
  return ir::kStatusOk;
}

}  // namespace mrh::world
