// SPDX-License-Identifier: Apache-2.0
// Shared fixtures of the Perturber tests: a busy scene, the forward-skip tolerance and body
// lookup by name.
#pragma once

#include <initializer_list>
#include <vector>

#include "mrh/world/world.h"

namespace mrh::world::testing {

// Contacts, friction, gravity, a tumbling body whose COM is off its origin, a slide-jointed cube
// and a row of touching boxes: everything that makes the constraint solve non-trivial.
inline constexpr char kBusy[] = R"(
<mujoco>
  <option timestep="0.02"/>
  <worldbody>
    <geom type="plane" size="5 5 0.1" friction="0.6 0.005 0.0001"/>
    <body name="resting" pos="0 0 0.0999" euler="0 0 10"><freejoint/>
      <geom type="box" size="0.1 0.1 0.1" mass="1"/></body>
    <body name="leaning" pos="0.18 0 0.35" euler="15 5 0"><freejoint/>
      <geom type="box" size="0.1 0.1 0.1" mass="0.7"/></body>
    <body name="tumbling" pos="-1 0.5 1"><freejoint/>
      <geom type="capsule" size="0.05 0.1" pos="0.1 0 0" mass="0.3"/>
      <geom type="sphere" size="0.05" pos="-0.05 0.05 0" mass="0.2"/></body>
    <body name="slider" pos="1 0 0.1">
      <joint type="slide" axis="1 0 0"/><joint type="slide" axis="0 1 0"/>
      <geom type="box" size="0.1 0.1 0.1" mass="3"/></body>
    <body name="row1" pos="0 1 0.0999"><freejoint/><geom type="box" size="0.1 0.1 0.1"/></body>
    <body name="row2" pos="0.2 1 0.0999"><freejoint/><geom type="box" size="0.1 0.1 0.1"/></body>
  </worldbody>
  <keyframe>
    <key name="moving"
         qpos="0 0 0.0999 0.996 0 0 0.087  0.18 0 0.35 0.98 0.13 0.04 0  -1 0.5 1 1 0 0 0
               0 0  0 1 0.0999 1 0 0 0  0.2 1 0.0999 1 0 0 0"
         qvel="0.1 0 0 0 0 0.5  0 0 0 0 0 0  0.3 -0.2 0.5 2 -3 5  0.2 0.1
               0 0 0 0 0 0  0 0 0 0 0 0"/>
  </keyframe>
</mujoco>)";

// Forward skipping against full steps: the same solver on the same inputs; only the velocity
// readout's roundoff differs (≈1e-16 m/s, divided by Δt and by |f| ≈ 1 N).
inline constexpr double kSkipTol = 1e-12;

inline std::vector<int> Bodies(const World& world, std::initializer_list<const char*> names) {
  std::vector<int> ids;
  for (const char* name : names) ids.push_back(world.FindBody(name));
  return ids;
}

}  // namespace mrh::world::testing
