// SPDX-License-Identifier: Apache-2.0
// The engine driven from the vendor's servo callback (OpenHaptics' scheduler owns the thread).
#include "servo_run.h"

#include <chrono>
#include <thread>

#include "mrh/device/external.h"
#include "mrh/world/world.h"

namespace mrh::cli {
namespace {

// How often the waiting thread reports progress; it does nothing else while the run goes on.
constexpr auto kProgressPeriod = std::chrono::milliseconds(50);

class EngineClient final : public device::ServoClient {
 public:
  explicit EngineClient(engine::Engine* engine) : engine_(engine) {}

  // Engine::Tick is RT-safe in real-time mode (it does not throw there).
  Wrench OnServoTick(double t, const device::DeviceState& reading) noexcept override {
    return engine_->Tick(t, reading);
  }

 private:
  engine::Engine* engine_;
};

}  // namespace

engine::RunStats RunOnServoThread(const session::Session& session, device::ServoDevice* device,
                                  physics::Recorder* recorder,
                                  const engine::Engine::ProgressFn& progress) {
  engine::Engine engine(session::LoadWorld(session),
                        std::make_unique<device::ExternalDevice>(device->specifications()),
                        session.device.calibration, session.engine);
  engine.Start(recorder);
  EngineClient client(&engine);
  device->SetServoClient(&client);
  try {
    device->Open();
  } catch (...) {
    device->SetServoClient(nullptr);
    (void)engine.Stop();
    throw;
  }
  const auto start = std::chrono::steady_clock::now();
  const std::chrono::duration<double> duration(session.engine.duration);
  for (auto now = start; now - start < duration; now = std::chrono::steady_clock::now()) {
    if (progress) progress((now - start) / duration);
    std::this_thread::sleep_for(kProgressPeriod);
  }
  device->Close();  // the scheduler has stopped: no more OnServoTick calls
  device->SetServoClient(nullptr);
  if (progress) progress(1.0);
  return engine.Stop();
}

}  // namespace mrh::cli
