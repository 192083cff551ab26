// SPDX-License-Identifier: Apache-2.0
// BuildGeometricIr: the internal builder behind a public one-shot call.
#include "mrh/engine/geometric_ir.h"

#include "geometric_ir_builder.h"

namespace mrh::engine {

void BuildGeometricIr(const world::World& world, int pointer_body,
                      const RenderingSettings& rendering, const Pose& X_WP,
                      ir::PhysicsSnapshot* out) {
  internal::GeometricIrBuilder builder(world, pointer_body, rendering);
  builder.Build(world, X_WP, out);
}

}  // namespace mrh::engine
