// SPDX-License-Identifier: Apache-2.0
// Per-geom haptic materials, and the check that every session material is used.
#include "material_table.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <set>
#include <string>

#include "mrh/core/error.h"
#include "mrh/physics/methods.h"
#include "mrh/world/world.h"

namespace mrh::physics {
namespace {

ir::ContactMaterial Resolve(const settings::MaterialSettings& m,
                            const settings::RenderingSettings& r) {
  ir::ContactMaterial out;
  out.has_material = true;
  out.stiffness = m.stiffness.value_or(r.stiffness);
  out.damping = m.damping.value_or(r.damping);
  out.friction = m.friction.value_or(r.friction);
  if (m.vibration) {
    out.vibration =
        ir::Vibration{m.vibration->amplitude, m.vibration->decay, m.vibration->frequency};
  }
  return out;
}

}  // namespace

void CheckMaterialsUsed(const world::World& world, const settings::RenderingSettings& rendering) {
  std::set<std::string> used;
  for (int g = 0; g < world.num_geoms(); ++g) {
    if (!world.geom(g).material.empty()) used.insert(world.geom(g).material);
  }
  for (const auto& [name, settings] : rendering.materials) {
    if (used.count(name) != 0) continue;
    throw InvalidArgument(fmt::format(
        "materials.{}: no geom of the scene uses the MJCF material \"{}\"; expected the name of "
        "a <material> that scene geoms use ({})",
        name, name,
        used.empty() ? "the scene's geoms use none" : fmt::format("{}", fmt::join(used, ", "))));
  }
}

}  // namespace mrh::physics

namespace mrh::physics::internal {

MaterialTable::MaterialTable(const world::World& world,
                             const settings::RenderingSettings& rendering)
    : by_geom_(static_cast<std::size_t>(world.num_geoms())) {
  if (rendering.materials.empty()) return;
  for (int g = 0; g < world.num_geoms(); ++g) {
    const auto it = rendering.materials.find(world.geom(g).material);
    if (it != rendering.materials.end()) {
      by_geom_[static_cast<std::size_t>(g)] = Resolve(it->second, rendering);
    }
  }
}

const ir::ContactMaterial& MaterialTable::of(int geom) const noexcept {
  if (geom < 0 || static_cast<std::size_t>(geom) >= by_geom_.size()) return none_;
  return by_geom_[static_cast<std::size_t>(geom)];
}

}  // namespace mrh::physics::internal
