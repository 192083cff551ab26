// SPDX-License-Identifier: Apache-2.0
// Embeds mrhaptics in real time: your 1 kHz loop moves the grip, a render thread reads the
// bodies' poses, and a user-interface thread changes the display gain while the engine runs.
//
//   realtime_embedding SESSION.json     e.g. scenes/t4_1_impulse.json
//
// The session runs in mode "realtime" (the physics on the engine's own thread) with an
// "external" device: this program's loop is the haptic thread. Nothing it does while the engine
// runs blocks that loop: the render thread reads poses through Engine::ReadBodyPoses (a
// lock-free triple buffer) and the gain changes through Engine::SetDisplayGain (one atomic).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <numbers>
#include <string>
#include <thread>

#include "mrh/core/error.h"
#include "mrh/device/device.h"
#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace {

// One line on stderr; a bad session or scene exits 2, any other failure 1.
int Fail(const std::exception& e, int code) {
  std::fprintf(stderr, "realtime_embedding: error: %s\n", e.what());
  return code;
}

using Clock = std::chrono::steady_clock;

// The grip's path in the device frame: 8 mm toward -x and back over two seconds, so the pointer
// presses into whatever lies on that side of it (the cube of scenes/t4_1.xml).
mrh::device::DeviceState Grip(double t) {
  constexpr double kDepth = 0.004;  // m; the path's amplitude (peak 2 * kDepth)
  const double w = std::numbers::pi;
  mrh::device::DeviceState reading;
  reading.X_DT.p = mrh::Vec3(-kDepth * (1.0 - std::cos(w * t)), 0.0, 0.0);
  reading.V_DT.v = mrh::Vec3(-kDepth * w * std::sin(w * t), 0.0, 0.0);
  return reading;
}

// The first body that can move (not static, not the pointer): the one the renderer reports.
int FirstMovingBody(const mrh::engine::Engine& engine) {
  const mrh::world::World& world = engine.world();
  for (int id = 1; id < world.num_bodies(); ++id) {
    const mrh::world::BodyInfo& body = world.body(id);
    if (!body.is_static && !body.is_mocap) return id;
  }
  return 0;
}

// Your renderer: draws the newest poses at its own rate (here 50 Hz, printing instead of
// drawing). One BodyPoses, reused, so that reading never allocates after the first call.
void RenderLoop(mrh::engine::Engine& engine, int body, const std::string& name,
                const std::atomic<bool>& done) {
  mrh::engine::BodyPoses poses;
  while (!done.load(std::memory_order_acquire)) {
    if (engine.ReadBodyPoses(&poses) && poses.step % 10 == 0) {
      const mrh::Vec3& p = poses.X_WB[static_cast<std::size_t>(body)].p;
      std::printf("render: step %lld t=%.2f s %s at (%.4f, %.4f, %.4f) m\n",
                  static_cast<long long>(poses.step), poses.t, name.c_str(), p.x(), p.y(), p.z());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

// Your user interface: halves the force the user feels one second in.
void UserInterface(mrh::engine::Engine& engine) {
  std::this_thread::sleep_for(std::chrono::seconds(1));
  engine.SetDisplayGain(0.5);
  std::printf("ui: display gain %.2f\n", engine.display_gain());
}

// Your servo loop: one tick per haptic_dt against absolute deadlines (no drift, no bursts).
// Returns the largest force displayed (N); `late` counts ticks started more than a period late.
double ServoLoop(mrh::engine::Engine& engine, const mrh::settings::EngineSettings& settings,
                 int* late) {
  const double dt = settings.haptic_dt;
  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(dt));
  const int ticks = static_cast<int>(std::lround(settings.duration / dt));
  double max_force = 0.0;
  const Clock::time_point start = Clock::now();
  for (int i = 0; i < ticks; ++i) {
    const Clock::time_point deadline = start + i * period;
    if (Clock::now() > deadline + period) ++*late;
    std::this_thread::sleep_until(deadline);
    const mrh::Wrench w = engine.Tick(i * dt, Grip(i * dt));  // read your device here
    // Command w.f (N) and w.tau (N·m) to your device here.
    max_force = std::max(max_force, w.f.norm());
  }
  return max_force;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: realtime_embedding SESSION.json\n");
    return 2;
  }
  try {
    const mrh::session::Session session = mrh::session::LoadSession(
        argv[1], {"device={\"type\": \"external\"}", "mode=realtime", "duration=2"});
    auto engine = mrh::session::MakeEngine(session);
    // What the renderer needs of the model, taken before the engine's threads run.
    const int body = FirstMovingBody(*engine);
    const std::string name = engine->world().body(body).name;
    std::atomic<bool> done{false};
    std::thread renderer([&] {
      RenderLoop(*engine, body, name, done);
    });
    engine->Start();
    std::thread ui([&] {
      UserInterface(*engine);
    });
    int late = 0;
    const double max_force = ServoLoop(*engine, session.engine, &late);
    const mrh::engine::RunStats stats = engine->Stop();
    ui.join();
    done.store(true, std::memory_order_release);
    renderer.join();
    std::printf("%lld ticks in %.2f s wall (%d late by more than a period), %lld physics steps, ",
                static_cast<long long>(stats.ticks), stats.wall_time, late,
                static_cast<long long>(stats.steps));
    std::printf("max displayed force %.3f N\n", max_force);
    return 0;
  } catch (const mrh::InvalidArgument& e) {
    return Fail(e, 2);
  } catch (const mrh::SceneError& e) {
    return Fail(e, 2);
  } catch (const std::exception& e) {
    return Fail(e, 1);
  }
}
