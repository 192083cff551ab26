// SPDX-License-Identifier: Apache-2.0
// ApplyReportImpulses: impulse J over one physics step as the constant wrench J/Δt^G.
#include "report_impulses.h"

#include "mrh/world/world.h"

namespace mrh::physics::internal {
namespace {

void ApplyImpulse(world::World& world, const ir::BodyImpulse& impulse, double dt) {
  world.AddWrenchAtCom(impulse.body, Wrench{impulse.linear / dt, impulse.angular / dt});
}

}  // namespace

void ApplyReportImpulses(world::World& world, const ir::HapticReport& report, double dt) {
  for (const ir::BodyImpulse& impulse : report.impulses) ApplyImpulse(world, impulse, dt);
}

void ApplyReportImpulses(world::World& world, const ir::HapticReport& report, double dt, int body) {
  for (const ir::BodyImpulse& impulse : report.impulses) {
    if (impulse.body == body) ApplyImpulse(world, impulse, dt);
  }
}

}  // namespace mrh::physics::internal
