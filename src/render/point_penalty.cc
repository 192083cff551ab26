// SPDX-License-Identifier: Apache-2.0
// The 3-DOF penalty renderer is header-only (inlined into the haptic tick); this unit anchors the
// module's library.
#include "mrh/render/point_penalty.h"
