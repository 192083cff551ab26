// SPDX-License-Identifier: Apache-2.0
// Experiment T4.6 (thesis §4.6.3): the 6×6 accelerance estimates measured
// instead of estimated: accuracy against converged MuJoCo and cost per physics step.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "experiment_table.h"
#include "experiment_util.h"
#include "experiments_impl.h"
#include "t4_6_impl.h"

namespace mrh::experiments::internal {
namespace {

using t4_6::kEstimateNames;
using t4_6::kNumEstimates;

// The accuracy cases: scenes/t4_push_box.xml and t4_push_row.xml (0.5 kg 10 cm boxes, μ 0.5,
// gravity, 20 ms; pyramidal cone), settled for 1 s, and the box pushed with |f| along unit(1, 0.3,
// −0.4) at a point 1 cm off its −x face centre in y and z. The free case lifts the box into zero
// gravity, reshapes it (half sizes kFreeHalf) and turns it (kFreeQuat) so that M⁻¹ is not diagonal.
struct Case {
  const char* name;
  const char* scene;
  double push = 1.0;  // N
  bool free = false;
  bool row = false;
};

constexpr Case kCases[] = {
    {"free-zero-g", "t4_push_box.xml", 1.0, true},
    // Half the push: the box's corner friction rows stay loaded under every test wrench.
    {"resting-half-push", "t4_push_box.xml", 0.5, false},
    {"resting", "t4_push_box.xml", 1.0, false},    // 0.96 N across < μN = 2.65 N: sticks
    {"sliding", "t4_push_box.xml", 4.0, false},    // 3.8 N across > μN = 3.25 N: slides
    {"row", "t4_push_row.xml", 1.0, false, true},  // the first of three touching boxes
};
constexpr double kFreeHalf[3] = {0.08, 0.05, 0.03};  // m
constexpr double kFreeQuat[4] = {0.9659258262890683, 0.14942924536134225, 0.14942924536134225,
                                 0.14942924536134225};  // 30° about unit(1, 1, 1)
constexpr double kBoxMass = 0.5;                        // kg, both scenes
constexpr int kSettleSteps = 50;                        // 1 s at 20 ms
// Bounds of the checks (docs/notes/accelerance-estimates.md): the analytic estimate is the exact
// linearization MuJoCo's converged step follows, so it may differ from the converged central
// differences only by their rounding (~1e-16 m/s over 2ε·Δt ~ 1e-5 m/s: ~1e-10).
constexpr double kExactTolerance = 1e-9;
constexpr double kReferenceTolerance = 1e-6;

std::string CaseScene(const std::filesystem::path& out, const Case& c) {
  const std::filesystem::path source = ScenesDir() / c.scene;
  std::string xml = ReadText(source);
  // The t4.push scenes use the elliptic cone; T4.6 runs MuJoCo's default pyramidal cone (as
  // T4.3 does), whose rows the analytic island estimate linearizes exactly (an elliptic cone's
  // rows are not piecewise quadratic: EstimateAnalytic reports ok = false there).
  xml = ReplaceOnce(xml, "cone=\"elliptic\"", "cone=\"pyramidal\"", source,
                    "t4.6 compares the estimates on the pyramidal friction cone");
  if (c.free) {
    const char* why = "t4.6 lifts the box into zero gravity, reshapes and turns it";
    xml = ReplaceOnce(xml, "gravity=\"0 0 -9.81\"", "gravity=\"0 0 0\"", source, why);
    xml = ReplaceOnce(xml, "<body name=\"box\" pos=\"0 0 0.05\">",
                      fmt::format("<body name=\"box\" pos=\"0 0 0.5\" quat=\"{} {} {} {}\">",
                                  kFreeQuat[0], kFreeQuat[1], kFreeQuat[2], kFreeQuat[3]),
                      source, why);
    xml = ReplaceAttribute(xml, "geom", "box", "size",
                           fmt::format("{} {} {}", kFreeHalf[0], kFreeHalf[1], kFreeHalf[2]),
                           source, why);
  }
  if (c.row) {
    // The scene's boxes just touch (the pointer closes the row); here they overlap by 1 mm so
    // that the row is in resting contact: the soft contact's push (~0.35 N) stays below the
    // floor's static friction (μ m g = 2.45 N), so the row stays pressed together.
    const char* why = "t4.6 presses the row's boxes together";
    xml = ReplaceOnce(xml, "pos=\"0.1 0 0.05\"", "pos=\"0.099 0 0.05\"", source, why);
    xml = ReplaceOnce(xml, "pos=\"0.2 0 0.05\"", "pos=\"0.198 0 0.05\"", source, why);
  }
  std::filesystem::create_directories(out / "scenes");
  const std::filesystem::path path = out / "scenes" / fmt::format("{}.xml", c.name);
  WriteText(path, xml);
  return path.string();
}

nlohmann::json MatrixJson(const Eigen::MatrixXd& A) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index r = 0; r < A.rows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index c = 0; c < A.cols(); ++c) row.push_back(A(r, c));
    rows.push_back(row);
  }
  return rows;
}

std::string Cell(const std::optional<double>& v) {
  return OptionalCell(v, "{:.3e}");
}

struct Tables {
  Table csv{{"case", "estimate", "rel_error_6x6", "rel_error_3x3", "steps", "forwards", "wall_ms",
             "island_dofs", "active_rows"}};
  Table md{{"case", "estimate", "6×6 rel. error", "3×3 rel. error", "MuJoCo steps", "forwards",
            "wall (ms)"}};
  Table plot{{"case", "full-1+18", "two-run", "analytic", "thesis-3dof-1+3 (3x3)"}};
  Table cost_csv{{"cubes", "estimate", "steps", "forwards", "estimate_ms", "global_ms", "occupancy",
                  "physics_dt"}};
  Table cost_md{{"cubes", "estimate", "MuJoCo steps + forwards", "estimate (ms)",
                 "global step (ms)", "occupancy"}};
};

double PointError(const Mat3& P, const Mat3& P_ref) {
  return (P - P_ref).norm() / P_ref.norm();
}

// One case measured at its settled state.
struct CaseRun {
  t4_6::Result ref;
  std::array<t4_6::Result, kNumEstimates> est;
  double lever = 0.0;                        // m
  world::Mat66 Minv = world::Mat66::Zero();  // the body's free-body inverse mass
};

CaseRun MeasureCase(const std::filesystem::path& out, const Case& c) {
  world::World world = world::World::LoadFile(CaseScene(out, c));
  const int body = world.FindBody("box");
  if (!c.free) {
    for (int i = 0; i < kSettleSteps; ++i) world.Step();
  }
  const double hx = c.free ? kFreeHalf[0] : 0.05;
  const t4_6::Push push{c.push * Vec3(1.0, 0.3, -0.4).normalized(),
                        world.body_state(body).p_WCm + Vec3(-hx, 0.01, 0.01)};
  CaseRun run;
  run.ref = t4_6::RunReference(&world, body, push);
  run.est = t4_6::RunEstimates(&world, body, push);
  run.lever = t4_6::Lever(world, body);
  run.Minv = world::FreeBodyInverseMass(world, body);
  return run;
}

// One estimate's table rows and summary entry; returns its plotted error (6×6, else 3×3).
double AddEstimate(const Case& c, int e, const CaseRun& run, Tables* tables, nlohmann::json* js) {
  const t4_6::Result& r = run.est[e];
  const std::optional<double> e6 =
      e == t4_6::kThesis3dof
          ? std::nullopt
          : std::optional<double>(world::RelativeError(r.A, run.ref.A, run.lever));
  const double e3 = PointError(r.point, run.ref.point);
  const double ms = static_cast<double>(r.cost.wall_ns) * 1e-6;
  const std::string steps = fmt::format("{}", r.cost.steps);
  const std::string forwards = fmt::format("{}", r.cost.forwards);
  tables->csv.Add({c.name, kEstimateNames[e], Cell(e6), Cell(e3), steps, forwards,
                   fmt::format("{:.4f}", ms), fmt::format("{}", r.island_dofs),
                   fmt::format("{}", r.active_rows)});
  tables->md.Add(
      {c.name, kEstimateNames[e], Cell(e6), Cell(e3), steps, forwards, fmt::format("{:.3f}", ms)});
  nlohmann::json& je = (*js)["estimates"][kEstimateNames[e]];
  je = {{"ok", r.ok},
        {"rel_error_3x3", e3},
        {"steps", r.cost.steps},
        {"forwards", r.cost.forwards},
        {"wall_ms", ms},
        {"point", MatrixJson(r.point)}};
  if (e6) {
    je["rel_error_6x6"] = *e6;
    je["A"] = MatrixJson(r.A);
  }
  return e6.value_or(e3);
}

// Free box: every estimate and the reference are M⁻¹; otherwise the analytic estimate is the
// converged step's linearization.
void AddCaseChecks(const Case& c, const CaseRun& run, Checks* checks) {
  if (c.free) {
    const double ref_err = world::RelativeError(run.ref.A, run.Minv, run.lever);
    checks->Add("free_reference_is_inverse_mass", ref_err <= kReferenceTolerance, ref_err,
                kReferenceTolerance);
    for (int e : {t4_6::kFull18, t4_6::kTwoRun, t4_6::kAnalytic}) {
      const double err = world::RelativeError(run.est[e].A, run.Minv, run.lever);
      checks->Add(fmt::format("free_{}_is_inverse_mass", kEstimateNames[e]), err <= kExactTolerance,
                  err, kExactTolerance);
    }
    return;
  }
  const t4_6::Result& analytic = run.est[t4_6::kAnalytic];
  const double err = world::RelativeError(analytic.A, run.ref.A, run.lever);
  checks->Add(std::string(c.name) + "_analytic_matches_converged",
              analytic.ok && err <= kReferenceTolerance, err, kReferenceTolerance);
}

// One case: reference and estimates at the settled state; rows, summary and checks.
void RunCase(const std::filesystem::path& out, const Case& c, Tables* tables,
             nlohmann::json* summary, Checks* checks) {
  const CaseRun run = MeasureCase(out, c);
  nlohmann::json& js = (*summary)["cases"][c.name];
  js["reference"] = {{"A", MatrixJson(run.ref.A)}, {"point", MatrixJson(run.ref.point)}};
  js["lever_m"] = run.lever;
  js["push_N"] = c.push;
  std::vector<std::string> plot_row = {c.name};
  for (int e = 0; e < kNumEstimates; ++e) {
    const double err = AddEstimate(c, e, run, tables, &js);
    plot_row.push_back(fmt::format("{:.3e}", std::max(err, 1e-16)));
  }
  tables->plot.Add(plot_row);
  AddCaseChecks(c, run, checks);
}

void RunCost(const std::filesystem::path& out, const T46Options& options, bool quiet,
             Tables* tables, nlohmann::json* summary) {
  for (const int cubes : options.cubes) {
    if (!quiet) std::cout << fmt::format("t4.6: cost with {} cubes...\n", cubes);
    for (const t4_6::CostRow& r : t4_6::MeasureCost(out, cubes, options.repetitions)) {
      tables->cost_csv.AddFormatted("{},{},{},{},{:.4f},{:.4f},{:.4f},{}", r.cubes, r.estimate,
                                    r.steps, r.forwards, r.estimate_ms, r.global_ms, r.occupancy,
                                    r.physics_dt);
      tables->cost_md.Add({fmt::format("{}", r.cubes), r.estimate,
                           fmt::format("{} + {}", r.steps, r.forwards),
                           fmt::format("{:.3f}", r.estimate_ms), fmt::format("{:.3f}", r.global_ms),
                           fmt::format("{:.3f}", r.occupancy)});
      (*summary)["cost"][std::to_string(r.cubes)][r.estimate] = {
          {"steps", r.steps},         {"forwards", r.forwards},   {"estimate_ms", r.estimate_ms},
          {"global_ms", r.global_ms}, {"occupancy", r.occupancy}, {"physics_dt", r.physics_dt}};
    }
  }
}

std::string T46Script() {
  return "# T4.6: accelerance estimates vs converged MuJoCo, and their occupancy.\n"
         "# Re-run with: gnuplot t4_6.gp\n"
         "set terminal pngcairo size 1100,900 enhanced font ',10'\nset output 't4_6.png'\n"
         "set datafile separator ','\nset grid ytics\nset key top left autotitle columnhead\n"
         "set style data histograms\nset style histogram clustered gap 1\n"
         "set style fill solid 0.8 border -1\nset multiplot layout 2,1\n"
         "set title 'Relative error vs converged MuJoCo (6x6, scaled by the radius of gyration; "
         "thesis-3dof: 3x3 point accelerance)'\n"
         "set logscale y\nset yrange [1e-16:1e3]\nset format y '10^{%L}'\nset ylabel 'relative "
         "error'\n"
         "plot 'errors_plot.csv' using 2:xtic(1), '' using 3, '' using 4, '' using 5\n"
         "unset logscale y\nset format y '%g'\nset yrange [0:*]\n"
         "set title 'Occupancy = (global step + estimate) / physics dt, one pushed cube'\n"
         "set ylabel 'occupancy'\nset xlabel 'cubes'\n"
         "plot 'cost_plot.csv' using 2:xtic(1), for [i=3:7] '' using i\n"
         "unset multiplot\n";
}

// cost_plot.csv: a row per cube count, a column per estimate (global-only first).
std::string CostPlotCsv(const nlohmann::json& cost) {
  std::string text = "cubes,global-only";
  for (const char* e : kEstimateNames) text += fmt::format(",{}", e);
  text += fmt::format(",{}\n", t4_6::kSharedForward);
  for (const auto& [cubes, rows] : cost.items()) {
    text += cubes + fmt::format(",{:.4f}", rows["global-only"]["occupancy"].get<double>());
    for (const char* e : kEstimateNames) {
      text += fmt::format(",{:.4f}", rows[e]["occupancy"].get<double>());
    }
    text += fmt::format(",{:.4f}\n", rows[t4_6::kSharedForward]["occupancy"].get<double>());
  }
  return text;
}

}  // namespace

int RunT46(const std::filesystem::path& out, bool quiet) {
  return RunT46(out, quiet, T46Options{});
}

int RunT46Full(const std::filesystem::path& out, bool quiet) {
  return RunT46(out, quiet, T46Options{.cubes = {10, 100}, .repetitions = 30});
}

int RunT46(const std::filesystem::path& out, bool quiet, const T46Options& options) {
  std::filesystem::create_directories(out);
  Tables tables;
  nlohmann::json summary;
  Checks checks;
  for (const Case& c : kCases) {
    if (!quiet) std::cout << "t4.6: " << c.name << "...\n";
    RunCase(out, c, &tables, &summary, &checks);
  }
  RunCost(out, options, quiet, &tables, &summary);
  WriteText(out / "accuracy.csv", tables.csv.Csv());
  WriteText(out / "accuracy.md", tables.md.Markdown());
  WriteText(out / "errors_plot.csv", tables.plot.Csv());
  WriteText(out / "cost.csv", tables.cost_csv.Csv());
  WriteText(out / "cost.md", tables.cost_md.Markdown());
  WriteText(out / "cost_plot.csv", CostPlotCsv(summary["cost"]));
  Plot(out, "t4_6", T46Script(), quiet);
  summary["experiment"] = "t4.6";
  summary["machine"] = MachineTag();
  summary["free_box"] = {{"mass_kg", kBoxMass},
                         {"half_sizes_m", {kFreeHalf[0], kFreeHalf[1], kFreeHalf[2]}},
                         {"quat_wxyz", {kFreeQuat[0], kFreeQuat[1], kFreeQuat[2], kFreeQuat[3]}}};
  if (!quiet) std::cout << tables.md.Markdown() << "\n" << tables.cost_md.Markdown();
  return FinishExperiment(out, std::move(summary), checks, quiet);
}

}  // namespace mrh::experiments::internal
