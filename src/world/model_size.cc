// SPDX-License-Identifier: Apache-2.0
// MuJoCo 2.2.2 buffer sizes (njmax, nconmax, nstack) from the scene: what its bodies need at
// rest with their neighbours, within what MuJoCo 2.2.2 can allocate.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <regex>
#include <string>

#include "mrh/core/error.h"
#include "world/world_impl.h"

namespace mrh::world::internal {
namespace {

// Contacts a moving geom of each type has, on average, resting on a floor among neighbours:
// MuJoCo 2.2 gives a box (or mesh, cylinder) face on a plane 4 contacts, a capsule lying 2, a
// sphere 1; one more for the neighbours it touches.
int ExpectedContacts(int geom_type) {
  switch (geom_type) {
    case mjGEOM_SPHERE:
    case mjGEOM_ELLIPSOID:
      return 2;
    case mjGEOM_CAPSULE:
      return 3;
    default:
      return 5;
  }
}

// Contacts a moving geom has at rest (the floor contacts alone): the constraint rows below this
// would drop resting contacts, so a scene that cannot hold them is refused.
int RestingContacts(int geom_type) {
  return std::max(1, ExpectedContacts(geom_type) - 1);
}

// Constraint rows of one contact of dimension `condim` under `cone` (MuJoCo 2.2.2: a pyramid has
// 2 (condim − 1) edges, an elliptic cone one row per dimension).
int RowsPerContact(int condim, int cone) {
  if (condim <= 1) return 1;
  return cone == mjCONE_ELLIPTIC ? condim : 2 * (condim - 1);
}

// Constraint rows that do not come from contacts: equality constraints, joint and tendon limits,
// dof and tendon friction loss.
std::int64_t OtherRows(const mjModel& m) {
  std::int64_t rows = 0;
  for (int e = 0; e < m.neq; ++e) {
    rows += m.eq_type[e] == mjEQ_WELD ? 6 : m.eq_type[e] == mjEQ_CONNECT ? 3 : 1;
  }
  for (int j = 0; j < m.njnt; ++j) rows += m.jnt_limited[j] ? 2 : 0;
  for (int t = 0; t < m.ntendon; ++t) {
    rows += (m.tendon_limited[t] ? 2 : 0) + (m.tendon_frictionloss[t] > 0.0 ? 1 : 0);
  }
  for (int i = 0; i < m.nv; ++i) rows += m.dof_frictionloss[i] > 0.0 ? 1 : 0;
  return rows;
}

// Bytes MuJoCo 2.2.2 allocates per njmax in mjData's buffer: dense efc_J and efc_JT (mjtNum) and
// their column indices (int), njmax × nv each; efc_AR and its indices, njmax × njmax; ~30
// per-row vectors.
std::int64_t ConstraintBytes(std::int64_t njmax, std::int64_t nv) {
  return njmax * (2 * (8 + 4) * nv + (8 + 4) * njmax + 30 * 8);
}

// mjData's buffer size is an int in MuJoCo 2.2.2: the constraint arrays must leave room below
// INT_MAX for the rest (contacts, bodies, geoms: a few MB even at 1000 bodies).
constexpr std::int64_t kBufferLimit = INT_MAX - (std::int64_t{64} << 20);

// The largest njmax whose constraint arrays fit under kBufferLimit with `nv` dofs.
std::int64_t MaxRows(std::int64_t nv, std::int64_t other_bytes) {
  std::int64_t lo = 0;
  std::int64_t hi = 1 << 20;
  while (lo < hi) {
    const std::int64_t mid = (lo + hi + 1) / 2;
    if (ConstraintBytes(mid, nv) + other_bytes <= kBufferLimit) {
      lo = mid;
    } else {
      hi = mid - 1;
    }
  }
  return lo;
}

bool HasAttribute(const std::string& size_element, const char* name) {
  return std::regex_search(size_element, std::regex(std::string("\\b") + name + "\\s*="));
}

std::string Gb(std::int64_t bytes) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.2f GB", static_cast<double>(bytes) / 1e9);
  return text.data();
}

}  // namespace

ExplicitSizes FindExplicitSizes(const std::string& mjcf) {
  static const std::regex kComment("<!--[\\s\\S]*?-->");
  static const std::regex kSize("<size\\b[^>]*>");
  const std::string text = std::regex_replace(mjcf, kComment, "");
  ExplicitSizes out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), kSize);
       it != std::sregex_iterator(); ++it) {
    const std::string element = it->str();
    out.njmax = out.njmax || HasAttribute(element, "njmax");
    out.nconmax = out.nconmax || HasAttribute(element, "nconmax");
    out.nstack = out.nstack || HasAttribute(element, "nstack");
  }
  return out;
}

BufferPlan PlanBuffers(const mjModel& m) {
  BufferPlan plan;
  int condim = 1;
  std::int64_t expected = 0;
  std::int64_t resting = 0;
  for (int g = 0; g < m.ngeom; ++g) {
    if (m.geom_contype[g] == 0 && m.geom_conaffinity[g] == 0) continue;
    condim = std::max(condim, m.geom_condim[g]);
    const int body = m.geom_bodyid[g];
    if (m.body_weldid[body] == 0 && m.body_mocapid[body] < 0) continue;  // static
    expected += ExpectedContacts(m.geom_type[g]);
    resting += RestingContacts(m.geom_type[g]);
  }
  for (int p = 0; p < m.npair; ++p) condim = std::max(condim, m.pair_dim[p]);
  const int rows = RowsPerContact(condim, m.opt.cone);
  const std::int64_t other = OtherRows(m);
  plan.nconmax = 2 * expected + m.npair + 100;
  const std::int64_t contact_bytes = plan.nconmax * static_cast<std::int64_t>(sizeof(mjContact));
  plan.resting_rows = rows * resting + other;
  plan.max_rows = MaxRows(m.nv, contact_bytes);
  plan.njmax = std::min(rows * expected + other + 100, plan.max_rows);
  plan.njmax = std::max<std::int64_t>(plan.njmax, std::min<std::int64_t>(500, plan.max_rows));
  plan.buffer_bytes = ConstraintBytes(plan.njmax, m.nv) + contact_bytes;
  // Stack (mjtNum) measured in MuJoCo 2.2.2 with 300-500 boxes: CG ~12 (nv + nefc), Newton
  // ~3 nv² (its dense Hessian), PGS ~1.5 nefc²; twice that, never below MuJoCo's small-scene
  // default. Untouched stack costs no memory.
  const double nv = m.nv;
  const double nj = static_cast<double>(plan.njmax);
  double stack = 1e6 + 30.0 * (nv + nj);
  if (m.opt.solver == mjSOL_NEWTON) stack += 6.0 * nv * nv;
  if (m.opt.solver == mjSOL_PGS) stack += 3.0 * nj * nj;
  plan.nstack = static_cast<std::int64_t>(std::min(stack, static_cast<double>(INT_MAX)));
  plan.stack_use = plan.nstack / 2;
  return plan;
}

void SizeBuffers(mjModel* m, const ExplicitSizes& explicit_sizes, const std::string& origin) {
  const BufferPlan plan = PlanBuffers(*m);
  if (!explicit_sizes.nconmax) m->nconmax = static_cast<int>(plan.nconmax);
  if (!explicit_sizes.nstack) m->nstack = static_cast<int>(plan.nstack);
  // A scene's own njmax was allocated by MuJoCo's compiler already (load.cc names it if not).
  if (explicit_sizes.njmax) return;
  if (plan.resting_rows > plan.max_rows) {
    throw SceneError(
        origin + ": the scene's resting contacts need ~" + std::to_string(plan.resting_rows) +
        " constraint rows (" + Gb(ConstraintBytes(plan.resting_rows, m->nv)) + " with " +
        std::to_string(m->nv) + " dofs), over the " + std::to_string(plan.max_rows) +
        " MuJoCo 2.2.2 can allocate (2.1 GB data limit); use fewer moving bodies, "
        "<option cone=\"elliptic\"> or condim=\"1\"");
  }
  m->njmax = static_cast<int>(plan.njmax);
}

}  // namespace mrh::world::internal
