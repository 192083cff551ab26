// SPDX-License-Identifier: Apache-2.0
// Experiment T4.3 (thesis §4.5.5, figs. 4.16–4.20): computation occupancy per physics step.
// The runs are in t4_3_run.cc, the reports in t4_3_report.cc.
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "experiment_util.h"
#include "t4_3_impl.h"

namespace mrh::experiments::internal {

using t4_3::AccuracyResult;
using t4_3::RunResult;

int RunT43(const std::filesystem::path& out, bool quiet) {
  return RunT43(out, quiet, T43Options{});
}

int RunT43Full(const std::filesystem::path& out, bool quiet) {
  T43Options options;
  options.cubes = {1, 10, 100, 500, 1000};
  options.friction_cubes = {1, 10, 100, 500};
  return RunT43(out, quiet, options);
}

namespace {

// Every (cubes, condim) set × variant, its scene written under out/scenes, grouped by variant
// (so that each variant's rows are consecutive for the scaling plot).
std::vector<RunResult> RunAll(const std::filesystem::path& out, const T43Options& options,
                              bool quiet) {
  std::vector<RunResult> runs;
  std::vector<std::pair<int, int>> sets;  // (cubes, condim)
  for (const int cubes : options.cubes) sets.emplace_back(cubes, 1);
  for (const int cubes : options.friction_cubes) sets.emplace_back(cubes, 3);
  for (const auto& [cubes, condim] : sets) {
    const std::filesystem::path scene =
        out / "scenes" / fmt::format("t4_3_{}.xml", t4_3::Key(cubes, condim));
    WriteText(scene, t4_3::SceneXml(cubes, condim));
    for (const std::string& variant : options.variants) {
      if (!quiet) {
        std::cout << fmt::format("t4.3: {} with {} cubes, condim {}...\n", variant, cubes, condim);
      }
      runs.push_back(t4_3::RunOne(scene, variant, cubes, condim, options));
    }
  }
  return runs;
}

void GroupByVariant(const T43Options& options, std::vector<RunResult>* runs) {
  std::stable_sort(runs->begin(), runs->end(), [&](const RunResult& a, const RunResult& b) {
    const auto rank = [&](const std::string& v) {
      return std::find(options.variants.begin(), options.variants.end(), v) -
             options.variants.begin();
    };
    return rank(a.variant) < rank(b.variant);
  });
}

// The accuracy runs at the largest frictionless cube count (none if accuracy_steps is 0).
std::vector<AccuracyResult> RunAccuracies(const std::filesystem::path& out,
                                          const T43Options& options, bool quiet) {
  std::vector<AccuracyResult> accuracy;
  if (options.accuracy_steps <= 0 || options.cubes.empty()) return accuracy;
  const int largest = *std::max_element(options.cubes.begin(), options.cubes.end());
  if (!quiet) std::cout << fmt::format("t4.3: accuracy check with {} cubes...\n", largest);
  const auto scene = out / "scenes" / fmt::format("t4_3_{}.xml", largest);
  const world::PerturberSettings mujoco = t4_3::MuJoCoSettings();
  const world::PerturberSettings converged = t4_3::ConvergedSettings();
  accuracy.push_back(t4_3::RunAccuracy(scene, largest, options, "island_vs_mujoco", {}, mujoco));
  accuracy.push_back(
      t4_3::RunAccuracy(scene, largest, options, "island_vs_converged", {}, converged));
  accuracy.push_back(
      t4_3::RunAccuracy(scene, largest, options, "mujoco_vs_converged", mujoco, converged));
  return accuracy;
}

}  // namespace

int RunT43(const std::filesystem::path& out, bool quiet, const T43Options& options) {
  std::filesystem::create_directories(out / "scenes");
  std::vector<RunResult> runs = RunAll(out, options, quiet);
  t4_3::PlotTimeSeries(out, runs, options, quiet);
  GroupByVariant(options, &runs);
  const std::vector<AccuracyResult> accuracy = RunAccuracies(out, options, quiet);
  nlohmann::json summary;
  const Checks checks = t4_3::WriteSummaries(out, runs, accuracy, options, quiet, &summary);
  t4_3::PlotScaling(out, options, quiet);
  return FinishExperiment(out, std::move(summary), checks, quiet);
}

}  // namespace mrh::experiments::internal
