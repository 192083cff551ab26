// SPDX-License-Identifier: Apache-2.0
// Adds a method and a device of your own (docs/architecture.md, "Adding a method" and "Adding a
// device"): registers "toy-plane" (toy_plane.h) and "toy-line" (toy_line.h), runs them on a
// session in lockstep, and prints what was displayed.
//
//   toy_method SESSION.json     e.g. scenes/t4_1_impulse.json
#include <cstdio>
#include <exception>

#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "toy_line.h"
#include "toy_plane.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: toy_method SESSION.json\n");
    return 2;
  }
  try {
    // Before the session is read: the parser checks the method's and the device's names.
    toy::RegisterToyPlane();
    toy::RegisterToyLine();
    const mrh::session::Session session = mrh::session::LoadSession(
        argv[1], {"method=toy-plane", "mode=lockstep",
                  R"(device={"type": "toy-line", "limits": {"max_force": 100}})"});
    const auto engine = mrh::session::MakeEngine(session);
    const mrh::engine::RunStats stats = engine->Run(nullptr);
    // The grip reaches the wall at x = 0.03 m (its 0.02 m sphere touches x = 0.05 m).
    std::printf("%s: %lld ticks, max force %.3f N\n", stats.method.c_str(),
                static_cast<long long>(stats.ticks), stats.max_force);
    for (const auto& [name, ticks] : stats.method_status) {
      std::printf("status %s: %lld ticks\n", name.c_str(), static_cast<long long>(ticks));
    }
    return stats.max_force > 0.0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "toy_method: error: %s\n", e.what());
    return 2;
  }
}
