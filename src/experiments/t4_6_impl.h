// SPDX-License-Identifier: Apache-2.0
// Experiment T4.6's private header: the estimates at one state and the cost runs (t4_6_cost.cc)
// shared with the driver (t4_6.cc). Not RT-safe; not thread-safe (one driver at a time).
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/world/accelerance.h"
#include "mrh/world/world.h"

namespace mrh::experiments::internal::t4_6 {

/// The estimates compared, in table order. "thesis-3dof" is the thesis' chapter-4 estimate (zero
/// run + 3 test forces, perturbation.h), which gives the 3×3 point accelerance only.
enum Estimate { kFull18, kTwoRun, kAnalytic, kThesis3dof, kNumEstimates };

inline constexpr std::array<const char*, kNumEstimates> kEstimateNames = {
    "full-1+18", "two-run", "analytic", "thesis-3dof-1+3"};

/// The analytic estimate whose forward pass is the next global step's own (mj_step = mj_forward
/// + integration): its cost without the forward pass.
inline constexpr const char* kSharedForward = "analytic-shared-forward";

/// The user's push on the body at the operating point: force f (N, world) at point p (m, world).
struct Push {
  Vec3 f = Vec3::Zero();
  Vec3 p_W = Vec3::Zero();
};

/// One estimate at one state: the 6×6 (zero for thesis-3dof), the 3×3 at the push point, cost.
struct Result {
  bool ok = false;
  world::Mat66 A = world::Mat66::Zero();
  Mat3 point = Mat3::Zero();
  world::EstimateCost cost;
  int island_dofs = 0, active_rows = 0;
};

/// The body's rms radius of gyration sqrt(tr I / 3m) (m): the torque arm of the 1 + 18 runs'
/// test torques and the length scale of the 6×6 errors.
double Lever(const world::World& world, int body);

/// The user's wrench of `push` about the body's COM (world).
Wrench PushWrench(const world::World& world, int body, const Push& push);

/// Every estimate of kEstimateNames at the world's current state (restored after each).
std::array<Result, kNumEstimates> RunEstimates(world::World* world, int body, const Push& push);

/// The converged reference at the operating point (user wrench applied).
Result RunReference(world::World* world, int body, const Push& push);

/// Cost of one estimate per physics step with `cubes` cubes (medians over the repetitions).
struct CostRow {
  int cubes = 0;
  std::string estimate;         ///< kEstimateNames, kSharedForward or "global-only"
  int steps = 0, forwards = 0;  ///< MuJoCo calls per physics step besides the global step
  double estimate_ms = 0.0;     ///< median wall time of the estimate
  double global_ms = 0.0;       ///< median wall time of the global step
  double occupancy = 0.0;       ///< (global + estimate) / physics_dt
  double physics_dt = 0.0;      ///< s
};

/// Writes t4.3's scene with `cubes` cubes (friction) under out/scenes, settles it, and times
/// `repetitions` physics steps: the global step and every estimate for the pushed cube.
std::vector<CostRow> MeasureCost(const std::filesystem::path& out, int cubes, int repetitions);

}  // namespace mrh::experiments::internal::t4_6
