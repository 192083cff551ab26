// SPDX-License-Identifier: Apache-2.0
// Validation of shape descriptions before they are prepared for distance queries.
#pragma once

#include "mrh/geometry/shape.h"

namespace mrh::geometry::internal {

/// Checks that `shape` describes a solid: finite sizes > 0 (a capsule's half-length may be 0) and,
/// for a mesh, at least 4 finite vertices and 4 triangles with indices in range.
/// @throws mrh::InvalidArgument naming the shape, the bad value and what was expected.
/// Not RT-safe.
void ValidateShape(const Shape& shape);

}  // namespace mrh::geometry::internal
