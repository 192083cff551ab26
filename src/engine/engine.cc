// SPDX-License-Identifier: Apache-2.0
// The engine: builds the method, then schedules its physics and haptic halves (thesis §4.1.3,
// fig. 4.5; the timing rule in docs/architecture.md).
#include "mrh/engine/engine.h"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

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

double PointerRadius(const world::World& world, int pointer_body,
                     const settings::PointerSettings& p) {
  if (p.radius > 0.0) return p.radius;
  for (int g : world.body(pointer_body).geoms) {
    const world::GeomInfo& geom = world.geom(g);
    if (geom.shape.type == geometry::ShapeType::kSphere) return geom.shape.size.x();
  }
  return 0.0;  // only 3-DOF methods need one (PointerRadiusFor3Dof)
}

// The pointer named `key` must be a mocap body whose geoms the world made non-colliding (pointer
// 0 through LoadOptions::pointer_body, the others through more_pointer_bodies).
int FindPointerBody(const world::World& world, const std::string& key, const std::string& body,
                    bool tool) {
  const int id = world.FindBody(body);
  if (id < 0 || !(world.body(id).is_mocap || tool)) {
    throw SceneError(
        fmt::format("{} = '{}' is not a mocap body of the scene; add <body name=\"{}\" "
                    "mocap=\"true\"> or name the right body",
                    key, body, body));
  }
  return id;
}

void CheckLanePointer(const world::World& world, int i, int body) {
  for (int g : world.body(body).geoms) {
    if (world.geom(g).collides) {
      throw SceneError(
          fmt::format("pointers[{}].body = '{}' still collides inside MuJoCo; load the world with "
                      "world::LoadOptions::more_pointer_bodies naming it (session::LoadWorld does)",
                      i, world.body(body).name));
    }
  }
}

}  // namespace

PointerLane::PointerLane(std::unique_ptr<device::Device> d, const device::Calibration& c)
    : device(std::move(d)), calibration(c), reports(kReportRingPeriods) {}

namespace {

// One device and one calibration per pointer, no device null.
void CheckDevices(int n, const std::vector<std::unique_ptr<device::Device>>& devices,
                  const std::vector<device::Calibration>& calibrations) {
  if (static_cast<int>(devices.size()) != n || static_cast<int>(calibrations.size()) != n) {
    throw InvalidArgument(fmt::format(
        "engine: {} pointer(s) but {} device(s) and {} calibration(s); give one of each per "
        "pointer (session::MakeEngine(session) builds them; the viewer and the Python module "
        "drive one pointer: keep one element in `pointers`)",
        n, devices.size(), calibrations.size()));
  }
  for (const auto& d : devices) {
    if (!d) throw InvalidArgument("engine: no device given");
  }
}

// Pointer i (>= 1)'s lane: its device, calibration, checked pointer body and radius.
std::unique_ptr<PointerLane> MakeLane(const world::World& world,
                                      const settings::EngineSettings& settings, int i,
                                      std::unique_ptr<device::Device> device,
                                      const device::Calibration& calibration) {
  auto lane = std::make_unique<PointerLane>(std::move(device), calibration);
  const settings::PointerSettings& p = settings.pointers[static_cast<std::size_t>(i)].pointer;
  lane->pointer_body = FindPointerBody(world, fmt::format("pointers[{}].body", i), p.body, false);
  CheckLanePointer(world, i, lane->pointer_body);
  lane->pointer_radius = PointerRadius(world, lane->pointer_body, p);
  return lane;
}

void CheckWatchdog(const settings::EngineSettings& settings) {
  if (settings.safety.watchdog_timeout <= 2.0 * settings.physics_dt) {
    throw InvalidArgument(fmt::format(
        "safety.watchdog_timeout = {} s must exceed 2 x physics_dt = {} s, or the watchdog "
        "fades the force in normal operation; raise it",
        settings.safety.watchdog_timeout, 2.0 * settings.physics_dt));
  }
}

// Every pointer's haptic side, pointer 0's first (after the methods are made).
void EmplaceHapticSides(EngineState* st) {
  const settings::EngineSettings& settings = st->settings;
  st->haptic.emplace(st->method.haptic.get(), st->device.get(), st->calibration, settings.safety,
                     st->ticks_per_step, settings.haptic_dt,
                     HapticSide::Exchange{&st->snapshots, &st->reports, &st->tick_records});
  for (std::size_t i = 0; i < st->lanes.size(); ++i) {
    PointerLane& lane = *st->lanes[i];
    lane.haptic.emplace(lane.haptic_method.get(), lane.device.get(), lane.calibration,
                        settings.safety, st->ticks_per_step, settings.haptic_dt,
                        HapticSide::Exchange{&lane.snapshots, &lane.reports, &st->tick_records,
                                             static_cast<int>(i) + 1});
  }
}

}  // namespace

EngineState::EngineState(world::World w, std::vector<std::unique_ptr<device::Device>> devices,
                         const std::vector<device::Calibration>& calibrations,
                         const settings::EngineSettings& s)
    : settings(s),
      world(std::move(w)),
      reports(kReportRingPeriods),
      tick_records(kTickRecordCapacity),
      body_poses(InitialBodyPoses(world)) {
  settings.Validate();
  const int n = settings.num_pointers();
  CheckDevices(n, devices, calibrations);
  if (n >= 2) {
    settings.pointer = settings.pointers[0].pointer;
    settings.rendering = settings.pointers[0].rendering;
  }
  device = std::move(devices[0]);
  calibration = calibrations[0];
  // virtual-coupling's tool is the pointer made a free body (world::LoadOptions::dynamic_pointer).
  const std::optional<MethodDescriptor> descriptor = FindMethod(settings.method);
  const bool tool = descriptor && descriptor->world.dynamic_pointer &&
                    world.FindBody(settings.pointer.body) == world.pointer_body();
  pointer_body = FindPointerBody(world, n >= 2 ? "pointers[0].body" : "pointer.body",
                                 settings.pointer.body, tool);
  pointer_radius = PointerRadius(world, pointer_body, settings.pointer);
  for (int i = 1; i < n; ++i) {
    lanes.push_back(MakeLane(world, settings, i, std::move(devices[static_cast<std::size_t>(i)]),
                             calibrations[static_cast<std::size_t>(i)]));
  }
  MakeMethodForSettings();
  CheckWatchdog(settings);
  ticks_per_step = settings.ticks_per_step();
  MakeLaneMethods();
  EmplaceHapticSides(this);
}

namespace {
std::vector<std::unique_ptr<device::Device>> OneDevice(std::unique_ptr<device::Device> device) {
  std::vector<std::unique_ptr<device::Device>> devices;
  devices.push_back(std::move(device));
  return devices;
}
}  // namespace

EngineState::EngineState(world::World w, std::unique_ptr<device::Device> d,
                         const device::Calibration& c, const settings::EngineSettings& s)
    : EngineState(std::move(w), OneDevice(std::move(d)), std::vector{c}, s) {}

void EngineState::MakeMethodForSettings() {
  physics::MethodContext context{&world, &settings, pointer_body, pointer_radius,
                                 device->specifications().max_force};
  if (!lanes.empty()) {
    context.pointers.push_back({pointer_body, pointer_radius, &settings.pointers[0].rendering});
    for (std::size_t i = 0; i < lanes.size(); ++i) {
      context.pointers.push_back(
          {lanes[i]->pointer_body, lanes[i]->pointer_radius, &settings.pointers[i + 1].rendering});
    }
  }
  world.set_timestep(settings.physics_dt);
  method = MakeMethod(settings.method, context);
  if (!lanes.empty() && !method.multi_pointer) {
    throw InvalidArgument(fmt::format(
        "pointers lists {} pointers, but method = \"{}\" renders one; use \"single-rate\", "
        "\"impulse\", \"local-dynamics\" (contact local model), \"local-dynamics-6dof\" or "
        "\"proxy-6dof\", or keep one pointer",
        lanes.size() + 1, settings.method));
  }
  if (method.single_rate && settings.physics_dt != settings.haptic_dt) {
    // The single-rate baseline steps the world at the haptic rate whatever physics_dt says.
    settings.physics_dt = settings.haptic_dt;
    world.set_timestep(settings.physics_dt);
    method = MakeMethod(settings.method, context);
  }
}

// Each further pointer's haptic half: the one the factory linked to pointer 0's, or else its
// method built for that pointer alone (its body, radius and rendering), whose physics half is
// dropped, as pointer 0's serves all.
void EngineState::MakeLaneMethods() {
  if (method.more_haptic.size() == lanes.size() && !lanes.empty()) {
    for (std::size_t i = 0; i < lanes.size(); ++i) {
      lanes[i]->haptic_method = std::move(method.more_haptic[i]);
    }
    return;
  }
  for (std::size_t i = 0; i < lanes.size(); ++i) {
    PointerLane& lane = *lanes[i];
    lane.settings = settings;
    lane.settings.pointer = settings.pointers[i + 1].pointer;
    lane.settings.rendering = settings.pointers[i + 1].rendering;
    lane.settings.pointers.clear();
    physics::MethodContext context{&world, &lane.settings, lane.pointer_body, lane.pointer_radius,
                                   lane.device->specifications().max_force};
    try {
      lane.haptic_method = MakeMethod(settings.method, context).haptic;
    } catch (const InvalidArgument& e) {
      throw InvalidArgument(fmt::format("pointers[{}]: {}", i + 1, e.what()));
    } catch (const SceneError& e) {
      throw SceneError(fmt::format("pointers[{}]: {}", i + 1, e.what()));
    }
  }
}

void EngineState::TickAll(double t) noexcept {
  haptic->Tick(t);
  for (const auto& lane : lanes) lane->haptic->Tick(t);
}

void EngineState::StopAll() noexcept {
  haptic->Stop();
  for (const auto& lane : lanes) lane->haptic->Stop();
}

void EngineState::OpenDevices() {
  device->Open();
  for (const auto& lane : lanes) lane->device->Open();
}

void EngineState::CloseDevices() {
  device->Close();
  for (const auto& lane : lanes) lane->device->Close();
}

void StartPhysics(EngineState& state, PhysicsSide& physics) {
  std::vector<ir::HapticReport> more;
  more.reserve(state.lanes.size());
  for (const auto& lane : state.lanes) more.push_back(lane->haptic->InitialReport(0.0));
  physics.Start(state.haptic->InitialReport(0.0), more);
}

}  // namespace internal

Engine::Engine(world::World world, std::unique_ptr<device::Device> device,
               const device::Calibration& calibration, const settings::EngineSettings& settings) {
  if (!device) throw InvalidArgument("engine: no device given");
  std::vector<std::unique_ptr<device::Device>> devices;
  devices.push_back(std::move(device));
  impl_ = std::make_unique<Impl>();
  impl_->state = std::make_unique<internal::EngineState>(std::move(world), std::move(devices),
                                                         std::vector{calibration}, settings);
}

Engine::Engine(world::World world, std::vector<std::unique_ptr<device::Device>> devices,
               const std::vector<device::Calibration>& calibrations,
               const settings::EngineSettings& settings) {
  impl_ = std::make_unique<Impl>();
  impl_->state = std::make_unique<internal::EngineState>(std::move(world), std::move(devices),
                                                         calibrations, settings);
}

int Engine::num_pointers() const {
  return 1 + static_cast<int>(impl_->state->lanes.size());
}

std::vector<std::string> Engine::pointer_names() const {
  const internal::EngineState& s = *impl_->state;
  std::vector<std::string> names{s.world.body(s.pointer_body).name};
  for (const auto& lane : s.lanes) names.push_back(s.world.body(lane->pointer_body).name);
  return names;
}

Engine::~Engine() = default;

const world::World& Engine::world() const {
  return impl_->state->world;
}

std::vector<std::string> Engine::setup_warnings() const {
  return impl_->state->method.physics->setup_warnings();
}

const settings::EngineSettings& Engine::settings() const {
  return impl_->state->settings;
}

double Engine::pointer_radius() const {
  return impl_->state->pointer_radius;
}

const haptic::MethodHaptic& Engine::haptic_method() const {
  return *impl_->state->method.haptic;
}

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
  for (const auto& lane : impl_->state->lanes) lane->haptic->SetDisplayGain(gain);
}

double Engine::display_gain() const {
  return impl_->state->haptic->display_gain();
}

RunStats Engine::Run(physics::Recorder* recorder, const ProgressFn& progress) {
  internal::EngineState& s = *impl_->state;
  if (s.has_run) {
    throw RuntimeError("Engine::Run called twice; build a new engine for another run");
  }
  s.has_run = true;
  s.OpenDevices();
  RunStats stats = s.settings.mode == settings::Mode::kLockstep
                       ? internal::RunLockstep(s, recorder, progress)
                       : internal::RunRealtime(s, recorder, progress);
  s.CloseDevices();
  return stats;
}

}  // namespace mrh::engine
