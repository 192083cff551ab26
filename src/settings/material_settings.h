// SPDX-License-Identifier: Apache-2.0
// Range checks of the haptic materials (session key `materials`).
#pragma once

#include "mrh/settings/settings.h"

namespace mrh::settings::internal {

/// Checks every material's gains against the ranges of their `rendering.*` counterparts and its
/// vibration (amplitude >= 0, decay > 0, 0 < frequency < 1 / (2 haptic_dt)).
/// @throws mrh::InvalidArgument naming `materials.NAME.key`, the value and the range.
void ValidateMaterials(const RenderingSettings& r, double haptic_dt);

}  // namespace mrh::settings::internal
