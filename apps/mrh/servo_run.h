// SPDX-License-Identifier: Apache-2.0
// `mrh run` with a device whose vendor scheduler owns the servo thread (openhaptics).
#pragma once

#include <memory>

#include "mrh/device/hardware.h"
#include "mrh/engine/engine.h"
#include "mrh/session/session.h"

namespace mrh::cli {

/// Runs the session's engine in embedded mode inside the device's servo callback: the engine's
/// haptic tick is the vendor's thread (Engine::Tick from ServoClient::OnServoTick), the calling
/// thread waits for settings.duration of wall time calling `progress`. Real-time mode only.
/// @throws what Engine::Start and Device::Open throw.
engine::RunStats RunOnServoThread(const session::Session& session, device::ServoDevice* device,
                                  physics::Recorder* recorder,
                                  const engine::Engine::ProgressFn& progress);

}  // namespace mrh::cli
