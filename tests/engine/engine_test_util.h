// SPDX-License-Identifier: Apache-2.0
// Shared fixtures of the engine tests: inline scenes and engine construction.
#pragma once

#include <memory>
#include <string>

#include "mrh/device/simulated.h"
#include "mrh/engine/engine.h"
#include "mrh/world/world.h"

namespace mrh::engine::testing {

/// The T4.1 world (thesis §4.5.3): zero gravity, 60 kg cube with rotation locked, moving at 0.017
/// m/s toward a fixed 0.02 m sphere pointer, 5 mm gap.
inline constexpr double kCubeMass = 60.0;
inline constexpr double kCubeSpeed = 0.017;

inline world::World T41World() {
  return world::World::LoadFile(std::string(MRH_SOURCE_DIR) + "/scenes/t4_1.xml");
}

inline settings::EngineSettings T41Settings(const std::string& method) {
  settings::EngineSettings s;
  s.method = method;
  s.physics_dt = 0.05;
  s.haptic_dt = 0.001;
  s.duration = 2.5;
  s.pointer.radius = 0.02;
  s.rendering.stiffness = 1000.0;
  s.rendering.damping = 0.0;
  // T4.1 measures the thesis' perturbation model (local-dynamics' other local model).
  s.rendering.local_model = settings::LocalModel::kPerturbation;
  s.safety.ramp = false;
  s.realtime_priority = false;
  return s;
}

inline std::unique_ptr<Engine> T41Engine(const settings::EngineSettings& settings) {
  world::World w = T41World();
  w.ApplyKeyframe("approach");
  device::Specifications specs;
  specs.max_force = 100.0;
  return std::make_unique<Engine>(std::move(w), device::MakeFixedDevice(Pose{}, specs),
                                  device::Calibration{}, settings);
}

}  // namespace mrh::engine::testing
