// SPDX-License-Identifier: Apache-2.0
// The haptic material of every geom of a world, resolved once at setup for the IR builders.
#pragma once

#include <vector>

#include "mrh/ir/material.h"
#include "mrh/settings/settings.h"

namespace mrh::world {
class World;
}

namespace mrh::physics::internal {

/// Per-geom ir::ContactMaterial: a geom whose MJCF material names a session material gets that
/// material with its unset gains filled from `rendering.*`; every other geom (no MJCF material,
/// or one the session does not name) gets none and is rendered with `rendering.*`. Built at
/// setup; read-only afterwards (the builders copy entries into the IR on the physics thread).
class MaterialTable {
 public:
  /// Not RT-safe (allocates). Does not check names; see CheckMaterialsUsed.
  MaterialTable(const world::World& world, const settings::RenderingSettings& rendering);

  /// The geom's material (none for an id outside the world). Thread-safe (const).
  const ir::ContactMaterial& of(int geom) const noexcept;

 private:
  std::vector<ir::ContactMaterial> by_geom_;
  ir::ContactMaterial none_;
};

}  // namespace mrh::physics::internal
