// SPDX-License-Identifier: Apache-2.0
// The size of MuJoCo's arena (contacts, constraint rows, solver stack) from the scene.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstdint>
#include <regex>
#include <string>

#include "world/world_impl.h"

namespace mrh::world::internal {
namespace {

// Arena bytes planned per moving collision geom. Measured on MuJoCo 3.14 (boxes resting on a
// floor with friction, pyramidal cones, Newton, islands): arena + stack use is ~15 KB per box at
// 2000 boxes (15 MB arena, 15 MB stack); 256 KiB leaves room for piles, condim 6 and meshes.
constexpr std::int64_t kBytesPerMovingGeom = std::int64_t{256} << 10;
// Every scene gets at least this much (MuJoCo's own default for a one-body scene is ~11 MB).
constexpr std::int64_t kMinArena = std::int64_t{16} << 20;

bool HasAttribute(const std::string& size_element, const char* name) {
  return std::regex_search(size_element, std::regex(std::string("\\b") + name + "\\s*="));
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
    out.memory = out.memory || HasAttribute(element, "memory");
    out.njmax = out.njmax || HasAttribute(element, "njmax");
    out.nconmax = out.nconmax || HasAttribute(element, "nconmax");
  }
  return out;
}

std::int64_t PlanArena(const mjModel& m) {
  std::int64_t moving = 0;
  for (int g = 0; g < m.ngeom; ++g) {
    if (m.geom_contype[g] == 0 && m.geom_conaffinity[g] == 0) continue;
    const int body = m.geom_bodyid[g];
    if (HasNoDofs(m, body) && m.body_mocapid[body] < 0) continue;  // static
    ++moving;
  }
  const std::int64_t plan = kMinArena + kBytesPerMovingGeom * moving;
  return std::min<std::int64_t>(plan, m.narena);
}

void SizeArena(mjModel* m, const ExplicitSizes& explicit_sizes) {
  if (explicit_sizes.any()) return;  // MuJoCo sized the arena from the scene's own <size>
  m->narena = PlanArena(*m);
}

}  // namespace mrh::world::internal
