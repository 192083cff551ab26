// SPDX-License-Identifier: Apache-2.0
// LiveSession: builds, starts, stops and restarts the embedded engine behind the viewer.
#include "viewer/live_session.h"

#include <string>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/device/external.h"
#include "mrh/device/simulated.h"
#include "mrh/engine/rt_clock.h"
#include "viewer/pointer_choice.h"

namespace mrh::viewer::internal {
namespace {

// A recorded tick file holds world-frame pointer poses; the engine expects device-frame readings
// (it applies the calibration), so replayed poses go back through the inverse calibration.
class WorldPoseSource final : public device::Device {
 public:
  WorldPoseSource(std::unique_ptr<device::Device> inner, const device::Calibration& calibration)
      : inner_(std::move(inner)), calibration_(calibration) {}

  const device::Specifications& specifications() const override { return inner_->specifications(); }

  device::DeviceState Read(double t) noexcept override {
    device::DeviceState s = inner_->Read(t);
    const Quat q_DW = calibration_.X_WD.q.conjugate();
    s.X_DT = calibration_.ToDevice(s.X_DT);
    s.V_DT = Twist{q_DW * s.V_DT.v / calibration_.scale, q_DW * s.V_DT.w};
    return s;
  }

  void SetWrench(const Wrench& w_D) noexcept override { inner_->SetWrench(w_D); }

 private:
  std::unique_ptr<device::Device> inner_;
  device::Calibration calibration_;
};

// The engine of a launch, with `external` as pointer `driven`'s device.
std::unique_ptr<engine::Engine> MakeEngine(const session::Session& session, int driven,
                                           world::World world,
                                           std::unique_ptr<device::Device> external,
                                           const settings::EngineSettings& s) {
  if (s.pointers.empty()) {
    return std::make_unique<engine::Engine>(std::move(world), std::move(external),
                                            session.device.calibration, s);
  }
  // The input drives the chosen pointer; every other pointer keeps its session device.
  std::vector<std::unique_ptr<device::Device>> devices;
  std::vector<device::Calibration> calibrations;
  for (int i = 0; i < static_cast<int>(s.pointers.size()); ++i) {
    devices.push_back(i == driven ? std::move(external) : session::MakePointerDevice(session, i));
    calibrations.push_back(PointerDevice(session, i).calibration);
  }
  return std::make_unique<engine::Engine>(std::move(world), std::move(devices), calibrations, s);
}

}  // namespace

const char* InputSourceName(InputSource source) noexcept {
  switch (source) {
    case InputSource::kMouse:
      return "mouse";
    case InputSource::kSession:
      return "session device";
    case InputSource::kReplay:
      return "replay";
  }
  return "?";
}

LiveSession::LiveSession(session::Session session, device::MouseDevice* mouse, LiveFeed* feed)
    : session_(std::move(session)), mouse_(mouse), feed_(feed), settings_(session_.engine) {
  settings_.mode = settings::Mode::kRealtime;
}

LiveSession::~LiveSession() {
  StopEngine();
  if (memory_locked_) engine::UnlockAllMemory();
}

void LiveSession::set_driven_pointer(int i) {
  driven_ = ChoosePointer(i, static_cast<int>(PointerNames(session_).size()));
}

void LiveSession::Start(InputSource source) {
  // Once for the viewer's lifetime, not per restart: mlockall faults in every mapped page.
  if (settings_.realtime_priority && !memory_locked_) {
    std::string why;  // a refusal shows in the panel's rates line (no "mlockall")
    memory_locked_ = engine::LockAllMemory(&why);
  }
  Launch(settings_, source, nullptr);
}

void LiveSession::Restart(const settings::EngineSettings& settings, InputSource source,
                          bool keep_world) {
  const world::World& world = engine_->world();
  StopEngine();  // the physics thread has joined: the world is ours to read
  world::Snapshot state = world.MakeSnapshot();
  world.Save(&state);
  const settings::EngineSettings previous_settings = settings_;
  const InputSource previous_source = source_;
  try {
    Launch(settings, source, keep_world ? &state : nullptr);
  } catch (const Error&) {
    Launch(previous_settings, previous_source, keep_world ? &state : nullptr);
    throw;
  }
}

std::unique_ptr<device::Device> LiveSession::MakeSource(InputSource source) const {
  switch (source) {
    case InputSource::kMouse:
      return nullptr;
    case InputSource::kSession:
      return session::MakePointerDevice(session_, driven_);
    case InputSource::kReplay: {
      const session::DeviceConfig& config = PointerDevice(session_, driven_);
      return std::make_unique<WorldPoseSource>(device::MakeReplayDevice(replay_file_, config.specs),
                                               config.calibration);
    }
  }
  return nullptr;
}

void LiveSession::Launch(const settings::EngineSettings& settings, InputSource source,
                         const world::Snapshot* state) {
  std::unique_ptr<device::Device> owned = MakeSource(source);
  // A real device (forcedimension, openhaptics, udp) connects here; simulated ones do nothing.
  if (owned) owned->Open();
  device::Device* input = owned ? owned.get() : mouse_;
  settings::EngineSettings s = settings;
  s.mode = settings::Mode::kRealtime;
  session::Session configured = session_;
  configured.engine = s;
  world::World world = session::LoadWorld(configured);
  if (state != nullptr) world.Restore(*state);
  auto external = std::make_unique<device::ExternalDevice>(PointerDevice(session_, driven_).specs);
  // Engine::Start reads the external device for the initial snapshot: give it the input's
  // first reading, or the first IR would be built around the device origin.
  external->Feed(input->Read(0.0));
  std::unique_ptr<engine::Engine> engine =
      MakeEngine(session_, driven_, std::move(world), std::move(external), s);
  feed_->set_time_offset(time_offset_);
  feed_->PublishWorld(engine->world());
  engine->Start(feed_);
  engine_ = std::move(engine);
  owned_source_ = std::move(owned);
  settings_ = s;
  source_ = source;
  loop_.Start(engine_.get(), input, s.haptic_dt, s.realtime_priority);
  ++starts_;
}

void LiveSession::StopEngine() {
  loop_.Stop();
  if (owned_source_) owned_source_->Close();  // zero output before the device is let go
  if (!engine_) return;
  const engine::RunStats stats = engine_->Stop();
  time_offset_ += static_cast<double>(stats.ticks) * settings_.haptic_dt;
}

}  // namespace mrh::viewer::internal
