// SPDX-License-Identifier: Apache-2.0
// T4.3's reports: the per-run time series, the occupancy tables, summary.json and the plots.
#include <fmt/format.h>

#include <algorithm>
#include <iostream>

#include "experiment_util.h"
#include "t4_3_impl.h"

namespace mrh::experiments::internal::t4_3 {
namespace {

std::string RunKey(const RunResult& r) {
  return Key(r.cubes, r.condim);
}

// runs/<variant>_<key>.csv: one row per physics step.
Table TimeSeries(const RunResult& r) {
  Table csv({"t", "compute_ms", "occupancy", "cpu_ms", "occupancy_cpu", "sim_contacts", "neighbors",
             "global_solver_iterations", "zero_force_solver_iterations",
             "test_run_solver_iterations", "test_runs"});
  for (const StepSample& s : r.samples) {
    csv.AddFormatted("{:.4f},{:.6f},{:.6f},{:.6f},{:.6f},{},{},{},{},{},{}", s.t, s.compute_ms,
                     s.compute_ms / (r.physics_dt * 1e3), s.cpu_ms, s.cpu_ms / (r.physics_dt * 1e3),
                     s.sim_contacts, s.neighbors, s.global_iterations, s.zero_iterations,
                     s.test_iterations, s.test_runs);
  }
  return csv;
}

// Figs. 4.17–4.20: occupancy vs time, one panel per cube count, one line per variant.
std::string TimeSeriesScript(const T43Options& options) {
  std::vector<std::pair<int, int>> sets;  // (cubes, condim) per panel
  for (const int cubes : options.cubes) sets.emplace_back(cubes, 1);
  for (const int cubes : options.friction_cubes) sets.emplace_back(cubes, 3);
  const std::size_t panels = sets.size();
  std::string plot = fmt::format(
      "# Thesis figs. 4.17-4.20: occupancy = step compute time / step. gnuplot occupancy_time.gp\n"
      "set terminal pngcairo size 1200,{} enhanced font ',10'\nset output 'occupancy_time.png'\n"
      "set datafile separator ','\nset grid\nset logscale y\nset yrange [1e-4:30]\n"
      "set key outside right\nset xlabel 't (s)'\nset ylabel 'occupancy'\n"
      "set multiplot layout {},1\n",
      300 * panels, panels);
  for (const auto& [cubes, condim] : sets) {
    plot += fmt::format(
        "set title '{} cube{}, condim {}'\nplot 1 with lines dt 2 lc 'black' title 'budget'", cubes,
        cubes == 1 ? "" : "s", condim);
    for (const std::string& v : options.variants) {
      plot += fmt::format(", 'runs/{}_{}.csv' using 1:3 with lines lw 2 title '{}'", Slug(v),
                          Key(cubes, condim), v);
    }
    plot += "\n";
  }
  return plot + "unset multiplot\n";
}

const RunResult* FindRun(const std::vector<RunResult>& runs, const std::string& v, int cubes,
                         int condim = 1) {
  for (const RunResult& r : runs) {
    if (r.variant == v && r.cubes == cubes && r.condim == condim) return &r;
  }
  return nullptr;
}

// occupancy_summary.csv and the first table of its .md (a row per run), summary["runs"].
// Returns whether every run is complete and finite.
bool OccupancyTables(const std::vector<RunResult>& runs, Table* csv, Table* md,
                     nlohmann::json* summary) {
  bool complete = true;
  for (const RunResult& r : runs) {
    const RunResult* impulse = FindRun(runs, "impulse", r.cubes, r.condim);
    const double ratio =
        impulse != nullptr && impulse->cpu_p50 > 0.0 ? r.cpu_p50 / impulse->cpu_p50 : 0.0;
    csv->AddFormatted("{},{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.3f},{}", r.variant,
                      r.cubes, r.physics_dt, r.samples.size(), r.p50, r.p99, r.max, r.cpu_p50,
                      r.cpu_max, ratio, r.condim);
    md->Add({r.variant, fmt::format("{}", r.cubes), fmt::format("{}", r.condim),
             fmt::format("{:g}", r.physics_dt * 1e3), fmt::format("{:.4f}", r.p50),
             fmt::format("{:.4f}", r.p99), fmt::format("{:.4f}", r.max),
             fmt::format("{:.4f}", r.cpu_p50), fmt::format("{:.4f}", r.cpu_max),
             fmt::format("{:.2f}", ratio)});
    (*summary)["runs"][r.variant][RunKey(r)] = {{"p50", r.p50},
                                                {"p99", r.p99},
                                                {"max", r.max},
                                                {"cpu_p50", r.cpu_p50},
                                                {"cpu_max", r.cpu_max},
                                                {"ratio_cpu_p50_to_impulse", ratio},
                                                {"steps", r.samples.size()},
                                                {"finite", r.finite}};
    complete = complete && r.finite;
  }
  return complete;
}

// The second table of occupancy_summary.md: local-dynamics' solver work per step, and
// summary["perturbation_work"].
Table WorkTable(const std::vector<RunResult>& runs, nlohmann::json* summary) {
  Table md({"local-dynamics", "cubes", "global-step iterations", "zero-force run",
            "per test run (mean)", "test runs per step", "test-run iterations / zero-force run"});
  for (const RunResult& r : runs) {
    if (r.variant != "local-dynamics" || r.test_runs == 0) continue;
    const auto steps = static_cast<double>(r.samples.size() - 1);
    const double per_run =
        static_cast<double>(r.test_iterations) / static_cast<double>(r.test_runs);
    const double ratio = r.zero_iterations > 0 ? static_cast<double>(r.test_iterations) /
                                                     static_cast<double>(r.zero_iterations)
                                               : 0.0;
    md.Add({"", RunKey(r), fmt::format("{:.1f}", static_cast<double>(r.global_iterations) / steps),
            fmt::format("{:.1f}", static_cast<double>(r.zero_iterations) / steps),
            fmt::format("{:.2f}", per_run),
            fmt::format("{:.1f}", static_cast<double>(r.test_runs) / steps),
            fmt::format("{:.3f}", ratio)});
    (*summary)["perturbation_work"][RunKey(r)] = {
        {"global_step_solver_iterations", r.global_iterations},
        {"zero_force_solver_iterations", r.zero_iterations},
        {"test_run_solver_iterations", r.test_iterations},
        {"test_runs", r.test_runs},
        {"steps", r.samples.size() - 1},
        {"test_run_iterations_per_run", per_run},
        {"test_run_iterations_over_zero_force", ratio},
        {"max_test_run_iterations_per_step", r.max_test_iterations_per_step}};
  }
  return md;
}

// The accuracy lines of occupancy_summary.md and summary["accuracy"].
std::string AccuracyLines(const std::vector<AccuracyResult>& accuracy, nlohmann::json* summary) {
  std::string md;
  for (const AccuracyResult& a : accuracy) {
    md += fmt::format(
        "\nAccuracy, {} ({} cubes, {} steps, {} measurements): |A - A_ref|/|A_ref| max {:.2e}, "
        "mean {:.2e}; |b - b_ref|/(1 + |b_ref|) max {:.2e}\n",
        a.name, a.cubes, a.steps, a.checks, a.max_rel_A, a.mean_rel_A, a.max_rel_b);
    (*summary)["accuracy"][a.name] = {{"cubes", a.cubes},           {"measurements", a.checks},
                                      {"steps", a.steps},           {"max_rel_A", a.max_rel_A},
                                      {"mean_rel_A", a.mean_rel_A}, {"max_rel_b", a.max_rel_b}};
  }
  return md;
}

// Deterministic checks of the essential result (counts, not wall time): every test-force run
// was solved on its island, with no MuJoCo solver iteration, and as accurately as converged.
Checks T43Checks(const std::vector<RunResult>& runs, const std::vector<AccuracyResult>& accuracy,
                 bool complete) {
  Checks checks;
  bool islands = true;
  for (const RunResult& r : runs) {
    if (r.variant != "local-dynamics") continue;
    islands = islands && r.test_runs > 0 && r.test_iterations == 0;
  }
  checks.Add("local_dynamics_test_runs_use_no_solver_iterations", islands);
  for (const AccuracyResult& a : accuracy) {
    if (a.name != "island_vs_converged") continue;
    checks.Add("island_accelerance_within_1e-4_of_converged",
               a.checks > 0 && a.max_rel_A <= kIslandAccuracyTol, a.max_rel_A, kIslandAccuracyTol);
  }
  checks.Add("all_runs_complete_and_finite", complete);
  return checks;
}

// Wall-clock goals are reported, never checked: this VM stalls for milliseconds at random.
void Goals(const std::vector<RunResult>& runs, const T43Options& options, nlohmann::json* summary) {
  const int largest = *std::max_element(options.cubes.begin(), options.cubes.end());
  if (const RunResult* ld = FindRun(runs, "local-dynamics", largest)) {
    (*summary)["goals"]["local_dynamics_p50_below_1_at_largest"] = ld->p50 < 1.0;
    (*summary)["goals"]["local_dynamics_cpu_p50_below_1_at_largest"] = ld->cpu_p50 < 1.0;
  }
  if (!options.friction_cubes.empty()) {
    const int most =
        *std::max_element(options.friction_cubes.begin(), options.friction_cubes.end());
    if (const RunResult* ld = FindRun(runs, "local-dynamics", most, 3)) {
      (*summary)["goals"]["local_dynamics_friction_p99_below_1_at_largest"] = ld->p99 < 1.0;
    }
  }
}

}  // namespace

std::string Key(int cubes, int condim) {
  return condim == 1 ? std::to_string(cubes) : fmt::format("{}_friction", cubes);
}

void PlotTimeSeries(const std::filesystem::path& out, const std::vector<RunResult>& runs,
                    const T43Options& options, bool quiet) {
  std::filesystem::create_directories(out / "runs");
  for (const RunResult& r : runs) {
    WriteText(out / "runs" / fmt::format("{}_{}.csv", Slug(r.variant), RunKey(r)),
              TimeSeries(r).Csv());
  }
  Plot(out, "occupancy_time", TimeSeriesScript(options), quiet);
}

// Median occupancy vs cube count, one line per variant (the thesis' comparison across counts).
void PlotScaling(const std::filesystem::path& out, const T43Options& options, bool quiet) {
  std::string plot =
      "# Median occupancy vs cube count (from occupancy_summary.csv). gnuplot "
      "occupancy_scaling.gp\n"
      "set terminal pngcairo size 900,600 enhanced font ',11'\n"
      "set output 'occupancy_scaling.png'\nset datafile separator ','\nset grid\n"
      "set logscale xy\nset xlabel 'cubes'\n"
      "set ylabel 'occupancy: CPU-time median (bar up to wall-time p99)'\n"
      "set key top left\nset title 'T4.3: computation occupancy per physics step'\n"
      "plot 1 with lines dt 2 lc 'black' title 'budget'";
  for (const int condim : {1, 3}) {
    if (condim == 3 && options.friction_cubes.empty()) continue;
    for (const std::string& v : options.variants) {
      plot += fmt::format(
          ", 'occupancy_summary.csv' using (strcol(1) eq '{}' && $11 == {} ? $2 : 1/0):8:8:6 "
          "with yerrorlines lw 2 {}title '{}{}'",
          v, condim, condim == 3 ? "dt 3 " : "", v, condim == 3 ? " (friction)" : "");
    }
  }
  Plot(out, "occupancy_scaling", plot + "\n", quiet);
}

Checks WriteSummaries(const std::filesystem::path& out, const std::vector<RunResult>& runs,
                      const std::vector<AccuracyResult>& accuracy, const T43Options& options,
                      bool quiet, nlohmann::json* summary) {
  Table csv({"variant", "cubes", "physics_dt_s", "steps", "p50", "p99", "max", "cpu_p50", "cpu_max",
             "ratio_cpu_p50_to_impulse", "condim"});
  Table occupancy({"variant", "cubes", "condim", "step (ms)", "occupancy p50", "p99", "max",
                   "CPU p50", "CPU max", "CPU p50 / impulse"});
  const bool complete = OccupancyTables(runs, &csv, &occupancy, summary);
  const std::string md = occupancy.Markdown() + "\n" + WorkTable(runs, summary).Markdown() +
                         AccuracyLines(accuracy, summary);
  WriteText(out / "occupancy_summary.csv", csv.Csv());
  WriteText(out / "occupancy_summary.md", md);
  Goals(runs, options, summary);
  (*summary)["experiment"] = "t4.3";
  (*summary)["machine"] = MachineTag();
  (*summary)["physics_dt_s"] = options.physics_dt;
  if (!quiet) std::cout << md;
  return T43Checks(runs, accuracy, complete);
}

}  // namespace mrh::experiments::internal::t4_3
