// SPDX-License-Identifier: Apache-2.0
// A haptic period's reaction impulses delivered to the world as constant wrenches (SPEC I5).
#pragma once

#include "mrh/ir/snapshot.h"

namespace mrh::world {
class World;
}

namespace mrh::physics::internal {

/// Adds each impulse J = (∫f dt, ∫τ dt about the COM) of `report` to `world` as the constant
/// wrench J/dt (world frame, torque about the body's COM) over the next World::Step, so that
/// the step of length dt (s) transfers exactly J. This is how the impulse-sending methods
/// deliver what the user pushed during the last haptic period (SPEC §3.6, I5, B4).
/// @pre dt > 0 is the world's step. Physics thread only; not RT-safe.
void ApplyReportImpulses(world::World& world, const ir::HapticReport& report, double dt);

/// As above, for the impulse of `body` only (the other bodies' entries are ignored).
/// Physics thread only; not RT-safe.
void ApplyReportImpulses(world::World& world, const ir::HapticReport& report, double dt, int body);

}  // namespace mrh::physics::internal
