// SPDX-License-Identifier: Apache-2.0
// Embeds mrhaptics in your own servo loop: load a session, feed device poses, read wrenches.
//
//   servo_loop SESSION.json     e.g. scenes/t4_1_impulse.json
//
// Your loop owns the device and the 1 kHz timing; mrhaptics runs the physics on its own thread
// (mode "realtime") or inline and deterministically (mode "lockstep", used here).
#include <cstdio>
#include <exception>

#include "mrh/core/error.h"
#include "mrh/device/device.h"
#include "mrh/engine/engine.h"
#include "mrh/session/session.h"

namespace {

// One line on stderr; a bad session or scene exits 2, any other failure 1.
int Fail(const std::exception& e, int code) {
  std::fprintf(stderr, "servo_loop: error: %s\n", e.what());
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: servo_loop SESSION.json\n");
    return 2;
  }
  try {
    // Replace the session's simulated device by the one this program drives.
    const mrh::session::Session session =
        mrh::session::LoadSession(argv[1], {"device={\"type\": \"external\"}"});
    auto engine = mrh::session::MakeEngine(session);
    engine->Start();

    const double dt = session.engine.haptic_dt;
    double max_force = 0.0;
    const int ticks = static_cast<int>(session.engine.duration / dt);
    for (int i = 0; i < ticks; ++i) {
      // Read your device here. This one holds the grip still at the device origin.
      mrh::device::DeviceState reading;
      const mrh::Wrench w = engine->Tick(i * dt, reading);
      // Command w.f (N) and w.tau (N·m) to your device here.
      max_force = w.f.norm() > max_force ? w.f.norm() : max_force;
    }
    const mrh::engine::RunStats stats = engine->Stop();
    std::printf("%lld ticks, %lld physics steps, max force %.3f N\n",
                static_cast<long long>(stats.ticks), static_cast<long long>(stats.steps),
                max_force);
    for (const auto& impulse : stats.impulses) {
      std::printf("impulse on %s: %.4f N*s\n", impulse.name.c_str(), impulse.linear.norm());
    }
    return 0;
  } catch (const mrh::InvalidArgument& e) {
    return Fail(e, 2);
  } catch (const mrh::SceneError& e) {
    return Fail(e, 2);
  } catch (const std::exception& e) {
    return Fail(e, 1);
  }
}
