// SPDX-License-Identifier: Apache-2.0
// The engine: builds the method, then schedules its physics and haptic halves (SPEC §4.9).
#include "mrh/engine/engine.h"

#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "engine_impl.h"
#include "mrh/core/error.h"
#include "mrh/world/world.h"

namespace mrh::engine {

namespace internal {
namespace {

// Capacity of the haptic → physics report ring, in periods: the physics side may fall this far
// behind before reports are dropped (and counted).
constexpr std::size_t kReportRingPeriods = 256;
// Tick records buffered between drains (~32 s at 1 kHz).
constexpr std::size_t kTickRecordCapacity = 1u << 15;

double PointerRadius(const world::World& world, int pointer_body, const EngineSettings& s) {
  if (s.pointer.radius > 0.0) return s.pointer.radius;
  for (int g : world.body(pointer_body).geoms) {
    const world::GeomInfo& geom = world.geom(g);
    if (geom.shape.type == geometry::ShapeType::kSphere) return geom.shape.size.x();
  }
  return 0.0;  // only 3-DOF methods need one (PointerRadiusFor3Dof)
}

}  // namespace

EngineState::EngineState(world::World w, std::unique_ptr<device::Device> d,
                         const device::Calibration& c, const EngineSettings& s)
    : settings(s),
      world(std::move(w)),
      device(std::move(d)),
      calibration(c),
      reports(kReportRingPeriods),
      tick_records(kTickRecordCapacity),
      body_poses(InitialBodyPoses(world)) {
  settings.Validate();
  pointer_body = world.FindBody(settings.pointer.body);
  // virtual-coupling's tool is the pointer made a free body (world::LoadOptions::dynamic_pointer).
  const bool tool = settings.method == "virtual-coupling" && pointer_body == world.pointer_body();
  if (pointer_body < 0 || !(world.body(pointer_body).is_mocap || tool)) {
    throw SceneError(fmt::format(
        "pointer.body = '{}' is not a mocap body of the scene; add <body name=\"{}\" "
        "mocap=\"true\"> or name the right body",
        settings.pointer.body, settings.pointer.body));
  }
  pointer_radius = PointerRadius(world, pointer_body, settings);
  MakeMethodForSettings();
  if (settings.safety.watchdog_timeout <= 2.0 * settings.physics_dt) {
    throw InvalidArgument(fmt::format(
        "safety.watchdog_timeout = {} s must exceed 2 x physics_dt = {} s, or the watchdog "
        "fades the force in normal operation; raise it",
        settings.safety.watchdog_timeout, 2.0 * settings.physics_dt));
  }
  ticks_per_step = settings.ticks_per_step();
  haptic.emplace(method.haptic.get(), device.get(), calibration, settings.safety, ticks_per_step,
                 settings.haptic_dt,
                 HapticSide::Exchange{&snapshots, &reports, &tick_records});
}

void EngineState::MakeMethodForSettings() {
  MethodContext context{&world, &settings, pointer_body, pointer_radius,
                        device->specifications().max_force};
  world.set_timestep(settings.physics_dt);
  method = MakeMethod(settings.method, context);
  if (method.single_rate && settings.physics_dt != settings.haptic_dt) {
    // The single-rate baseline steps the world at the haptic rate whatever physics_dt says.
    settings.physics_dt = settings.haptic_dt;
    world.set_timestep(settings.physics_dt);
    method = MakeMethod(settings.method, context);
  }
}

}  // namespace internal

Engine::Engine(world::World world, std::unique_ptr<device::Device> device,
               const device::Calibration& calibration, const EngineSettings& settings) {
  if (!device) throw InvalidArgument("engine: no device given");
  impl_ = std::make_unique<Impl>();
  impl_->state = std::make_unique<internal::EngineState>(std::move(world), std::move(device),
                                                         calibration, settings);
}

Engine::~Engine() = default;

const world::World& Engine::world() const { return impl_->state->world; }

const EngineSettings& Engine::settings() const { return impl_->state->settings; }

double Engine::pointer_radius() const { return impl_->state->pointer_radius; }

const haptic::MethodHaptic& Engine::haptic_method() const { return *impl_->state->method.haptic; }

const physics::MethodPhysics& Engine::physics_method() const {
  return *impl_->state->method.physics;
}

void Engine::RequestStop() noexcept {
  impl_->state->stop_requested.store(true, std::memory_order_relaxed);
}

bool Engine::ReadBodyPoses(BodyPoses* out) {
  TripleBuffer<BodyPoses>& poses = impl_->state->body_poses;
  const bool fresh = poses.Update();
  // Same-sized vectors: the copy reuses out's storage after the first call.
  *out = poses.read_slot();
  return fresh;
}

void Engine::SetDisplayGain(double gain) {
  if (!std::isfinite(gain) || gain < 0.0) {
    throw InvalidArgument(fmt::format(
        "Engine::SetDisplayGain: gain = {}; expected a finite value >= 0 (1 displays the "
        "rendered wrench unchanged)",
        gain));
  }
  impl_->state->haptic->SetDisplayGain(gain);
}

double Engine::display_gain() const { return impl_->state->haptic->display_gain(); }

RunStats Engine::Run(Recorder* recorder, const ProgressFn& progress) {
  internal::EngineState& s = *impl_->state;
  if (s.has_run) {
    throw RuntimeError("Engine::Run called twice; build a new engine for another run");
  }
  s.has_run = true;
  s.device->Open();
  RunStats stats = s.settings.mode == Mode::kLockstep ? internal::RunLockstep(s, recorder, progress)
                                                      : internal::RunRealtime(s, recorder, progress);
  s.device->Close();
  return stats;
}

}  // namespace mrh::engine
