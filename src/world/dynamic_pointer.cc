// SPDX-License-Identifier: Apache-2.0
// Virtual coupling's dynamic tool: the pointer's mocap body rewritten as a free body.
#include <mujoco/mujoco.h>

#include <regex>
#include <string>

#include "mrh/core/error.h"
#include "mrh/core/validate.h"
#include "world/world_impl.h"

namespace mrh::world::internal {

std::string MakePointerDynamic(const std::string& xml, const std::string& name,
                               const std::string& origin) {
  // The body's start tag: <body ... name="NAME" ...>.
  const std::regex tag("<body\\b[^>]*\\bname\\s*=\\s*\"" +
                       std::regex_replace(name, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
                       "\"[^>]*>");
  std::smatch match;
  if (!std::regex_search(xml, match, tag) || match.str().ends_with("/>")) {
    throw SceneError(origin + ": pointer body '" + name + "' has no <body name=\"" + name +
                     "\" ...> element with children to make a "
                     "dynamic tool of (virtual-coupling); give it its geoms as children");
  }
  std::string start = std::regex_replace(match.str(), std::regex("\\bmocap\\s*=\\s*\"true\""), "");
  return xml.substr(0, static_cast<std::size_t>(match.position())) + start + "<freejoint/>" +
         match.suffix().str();
}

void SetUpDynamicPointer(mjModel* m, int body, const LoadOptions& options,
                         const std::string& origin, BodyInfo* info) {
  if (m->body_jntnum[body] != 1 || m->jnt_type[m->body_jntadr[body]] != mjJNT_FREE) {
    throw SceneError(origin + ": pointer body '" + info->name +
                     "' must be a top-level body without joints for virtual-coupling");
  }
  if (options.tool_mass > 0.0) {
    const double scale = m->body_mass[body] > 0.0 ? options.tool_mass / m->body_mass[body] : 0.0;
    m->body_mass[body] = options.tool_mass;
    for (int i = 0; i < 3; ++i) m->body_inertia[3 * body + i] *= scale;
  }
  if (!options.tool_inertia.isZero(0.0)) {
    for (int i = 0; i < 3; ++i) m->body_inertia[3 * body + i] = options.tool_inertia[i];
  }
  const Vec3 inertia(m->body_inertia[3 * body], m->body_inertia[3 * body + 1],
                     m->body_inertia[3 * body + 2]);
  if (!(m->body_mass[body] > 0.0) || !(inertia.minCoeff() > 0.0)) {
    throw SceneError(origin + ": pointer body '" + info->name + "' has mass " +
                     FormatNumber(m->body_mass[body]) + " kg and inertia " +
                     FormatNumbers(inertia.data(), 3) +
                     " kg*m^2; virtual-coupling needs a tool with mass and inertia > 0: give its "
                     "geoms a density or set rendering.tool_mass and rendering.tool_inertia");
  }
  // The tool must touch the scene inside MuJoCo: a pointer geom that collides with nothing (as
  // the IR-based methods' pointers usually are, contype = conaffinity = 0) collides as a default
  // geom (1, 1) instead.
  for (int g = 0; g < m->ngeom; ++g) {
    const bool silent = m->geom_contype[g] == 0 && m->geom_conaffinity[g] == 0;
    if (m->geom_bodyid[g] != body || !silent) continue;
    m->geom_contype[g] = 1;
    m->geom_conaffinity[g] = 1;
  }
  RefreshBodyCollisionMasks(m, body);
  info->mass = m->body_mass[body];
  const Mat3 R = Quat(m->body_iquat[4 * body], m->body_iquat[4 * body + 1],
                      m->body_iquat[4 * body + 2], m->body_iquat[4 * body + 3])
                     .toRotationMatrix();
  info->inertia_B = R * inertia.asDiagonal() * R.transpose();
}

}  // namespace mrh::world::internal
