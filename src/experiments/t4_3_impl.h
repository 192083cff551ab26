// SPDX-License-Identifier: Apache-2.0
// Experiment T4.3's private header: the runs (t4_3_run.cc), the reports (t4_3_report.cc) and
// the driver (t4_3.cc) share these types. Not RT-safe; not thread-safe (one driver at a time).
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "experiment_table.h"
#include "experiments_impl.h"
#include "mrh/world/perturbation.h"

namespace mrh::experiments::internal::t4_3 {

constexpr const char* kNoPerturbation = "local-dynamics/no-perturbation";
// Check on the island solve against the converged reference: that reference itself settles to
// ~1e-5 (2e-5 at 1000 cubes), so 1e-4 leaves room for it and still catches a real error.
constexpr double kIslandAccuracyTol = 1e-4;

struct StepSample {
  double t = 0.0, compute_ms = 0.0, cpu_ms = 0.0;
  int sim_contacts = 0, neighbors = 0;
  // MuJoCo solver iterations (local-dynamics with perturbations only): of the real global step,
  // of the zero-force run, and summed over the test-force runs, and the number of those runs.
  int global_iterations = 0, zero_iterations = 0, test_iterations = 0, test_runs = 0;
};

struct RunResult {
  std::string variant;
  int cubes = 0;
  double physics_dt = 0.0;
  int condim = 1;
  std::vector<StepSample> samples;
  double p50 = 0.0, p99 = 0.0, max = 0.0;  // occupancy from wall time, steps ≥ 1
  double cpu_p50 = 0.0, cpu_max = 0.0;     // occupancy from thread CPU time, steps ≥ 1
  bool finite = true;
  // Solver iterations over steps ≥ 1 (local-dynamics with perturbations): the global steps', the
  // zero-force runs' and the test-force runs' (and how many of those ran).
  std::int64_t global_iterations = 0, zero_iterations = 0, test_iterations = 0, test_runs = 0;
  int max_test_iterations_per_step = 0;
};

// One accuracy run: every measurement of `used` compared with `reference` at the same state
// and test forces.
struct AccuracyResult {
  std::string name;
  int cubes = 0, steps = 0;
  std::int64_t checks = 0;
  double max_rel_A = 0.0, mean_rel_A = 0.0, max_rel_b = 0.0;
};

/// The T4.3 scene: `cubes` 0.1 m cubes on a floor (condim 1 or 3) and the pointer sphere.
std::string SceneXml(int cubes, int condim);

/// One run of `variant` on `scene`: step samples, occupancy statistics, solver work.
RunResult RunOne(const std::filesystem::path& scene, const std::string& variant, int cubes,
                 int condim, const T43Options& options);

/// The perturbation settings of the accuracy runs: every test-force run a MuJoCo solve from the
/// saved warm start, and that one converged (the reference).
world::PerturberSettings MuJoCoSettings();
world::PerturberSettings ConvergedSettings();

/// One accuracy run: every measurement of `used` compared with `reference` at the same state
/// and test forces, over options.accuracy_steps steps.
AccuracyResult RunAccuracy(const std::filesystem::path& scene, int cubes, const T43Options& options,
                           const std::string& name, const world::PerturberSettings& used,
                           const world::PerturberSettings& reference);

/// A run's name in file names and summary keys: the cube count, "_friction" for condim 3.
std::string Key(int cubes, int condim);

/// runs/<variant>_<key>.csv per run and occupancy_time.png (figs. 4.17–4.20).
void PlotTimeSeries(const std::filesystem::path& out, const std::vector<RunResult>& runs,
                    const T43Options& options, bool quiet);

/// occupancy_scaling.png from occupancy_summary.csv.
void PlotScaling(const std::filesystem::path& out, const T43Options& options, bool quiet);

/// Writes occupancy_summary.csv/.md and fills `summary` (runs, perturbation work, accuracy,
/// goals); returns the checks. Prints the Markdown unless `quiet`.
Checks WriteSummaries(const std::filesystem::path& out, const std::vector<RunResult>& runs,
                      const std::vector<AccuracyResult>& accuracy, const T43Options& options,
                      bool quiet, nlohmann::json* summary);

}  // namespace mrh::experiments::internal::t4_3
