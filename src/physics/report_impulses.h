// SPDX-License-Identifier: Apache-2.0
// A haptic period's reaction impulses delivered to the world as constant wrenches over the next
// physics step (the thesis' one-step-late reaction, §3.5).
#pragma once

#include "mrh/ir/snapshot.h"

namespace mrh::world {
class World;
}

namespace mrh::physics::internal {

/// Adds each impulse J = (∫f dt, ∫τ dt about the COM) of `report` to `world` as the constant
/// wrench J/dt (world frame, torque about the body's COM) over the next World::Step, so that
/// the step of length dt (s) transfers exactly J. This is how the impulse-sending methods
/// deliver what the user pushed during the last haptic period (thesis §3.5; B4, Hasegawa et
/// al. 1999, thesis ref. [35]).
/// @pre dt > 0 is the world's step. Physics thread only; not RT-safe.
void ApplyReportImpulses(world::World& world, const ir::HapticReport& report, double dt);

/// As above, for the impulse of `body` only (the other bodies' entries are ignored).
/// Physics thread only; not RT-safe.
void ApplyReportImpulses(world::World& world, const ir::HapticReport& report, double dt, int body);

}  // namespace mrh::physics::internal
