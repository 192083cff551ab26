// SPDX-License-Identifier: Apache-2.0
// BuildGeometricIr: the internal builder behind a public one-shot call.
#include "mrh/physics/geometric_ir.h"

#include "geometric_ir_builder.h"

namespace mrh::physics {

void BuildGeometricIr(const world::World& world, int pointer_body,
                      const settings::RenderingSettings& rendering, const Pose& X_WP,
                      ir::PhysicsSnapshot* out) {
  internal::GeometricIrBuilder builder(world, pointer_body, rendering);
  builder.Build(world, X_WP, out);
}

}  // namespace mrh::physics
