// SPDX-License-Identifier: Apache-2.0
// Experiment t3.7's report: tables, plots and the acceptance checks over the runs of t3_7.cc.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>

#include "experiment_table.h"
#include "experiment_util.h"
#include "t3_7_impl.h"

namespace mrh::experiments::internal {
namespace {

std::string PlotScript(const std::vector<Case>& cases) {
  std::string gp = fmt::format(
      "# t3.7: |f|, object x and y per case and method. gnuplot t3_7.gp\n"
      "set terminal pngcairo size 1500,{} enhanced font ',9'\nset output 't3_7.png'\n"
      "set datafile separator ','\nset grid\nset key top left\nset multiplot layout {},3\n",
      240 * cases.size(), cases.size());
  const auto panel = [&](const Case& c, const char* what, const char* file, int column) {
    gp += fmt::format("set title '{}: {}' noenhanced\nset xlabel 't (s)'\nplot ", c.Name(), what);
    for (std::size_t i = 0; i < std::size(kVariants); ++i) {
      gp += fmt::format("{}'runs/{}_{}.csv' using 1:{} with lines title '{}' noenhanced",
                        i ? ", " : "", RunSlug(c, kVariants[i]), file, column, kVariants[i].label);
    }
    gp += "\n";
  };
  for (const Case& c : cases) {
    panel(c, "|f| (N)", "force", 2);
    panel(c, "object x (m)", "object", 2);
    panel(c, "object y (m)", "object", 3);
  }
  return gp + "unset multiplot\n";
}

std::string Cell(const std::optional<double>& x, const char* f) {
  return x ? fmt::format(fmt::runtime(f), *x) : std::string("—");
}

const char* Flag(const std::optional<bool>& b) {
  return b ? (*b ? "1" : "0") : "";
}

// The verdict column: what a run got wrong, or empty.
std::string VerdictText(const T37Verdict& v) {
  std::string verdict;
  const auto note = [&](bool bad, const char* what) {
    if (bad) verdict += (verdict.empty() ? "" : ", ") + std::string(what);
  };
  note(v.thrown, "thrown");
  note(v.spun, "spun");
  note(v.slide_ok && !*v.slide_ok, "not μmg");
  note(v.follows_ref && !*v.follows_ref, "off ref");
  note(v.same_turn && !*v.same_turn, "turns the other way");
  return verdict;
}

Table CsvTable() {
  return Table({"case", "method", "mean_force_N", "sd_force_N", "coulomb_force_N", "slide_error",
                "impulse_Ns", "impulse_vs_ref", "peak_speed_mps", "peak_spin_radps", "end_x_m",
                "end_y_m", "end_yaw_rad", "pose_error_m", "thrown", "spun", "follows_ref",
                "same_turn"});
}

Table MdTable() {
  return Table({"case", "method", "mean |f| 2–5 s (N)", "sd (N)", "vs μmg", "∫f dt (x, y) (N·s)",
                "vs ref", "peak speed (m/s)", "peak spin (rad/s)", "end (x, y) (m)", "yaw (°)",
                "pos. error (m)", "verdict"});
}

void AddCsvRow(Table* csv, const std::string& name, const T37Result& r, const T37Verdict& v) {
  csv->AddFormatted(
      "{},{},{:.4f},{:.4f},{:.4f},{},{:.4f},{},{:.4f},{:.3f},{:.4f},{:.4f},{:.4f},{},{},{},{},{"
      "}",
      name, r.method, r.mean_f, r.sd_f, r.coulomb_f, Cell(v.slide_error, "{:.4f}"),
      r.impulse.norm(), Cell(v.force_vs_ref, "{:.4f}"), r.peak_speed, r.peak_spin, r.end.x(),
      r.end.y(), r.yaw, Cell(v.pose_error, "{:.4f}"), v.thrown ? 1 : 0, v.spun ? 1 : 0,
      Flag(v.follows_ref), Flag(v.same_turn));
}

// Row k of a case (k = 0 the reference, which has nothing to compare with).
void AddMdRow(Table* md, const std::string& name, const T37Result& r, const T37Verdict& v,
              std::size_t k) {
  const std::string verdict = VerdictText(v);
  md->Add({name, r.method, fmt::format("{:.3f}", r.mean_f), fmt::format("{:.3f}", r.sd_f),
           v.slide_error ? fmt::format("{:+.1f} %", 100 * *v.slide_error) : "—",
           fmt::format("({:.2f}, {:.2f})", r.impulse.x(), r.impulse.y()),
           k > 0 && v.force_vs_ref ? fmt::format("{:.1f} %", 100 * *v.force_vs_ref) : "—",
           fmt::format("{:.3f}", r.peak_speed), fmt::format("{:.2f}", r.peak_spin),
           fmt::format("({:.3f}, {:.3f})", r.end.x(), r.end.y()),
           fmt::format("{:.0f}", r.yaw * 180.0 / std::numbers::pi),
           k > 0 ? Cell(v.pose_error, "{:.4f}") : "—", verdict.empty() ? "ok" : verdict});
}

nlohmann::json SummaryOf(const T37Result& r, const T37Verdict& v) {
  return {{"mean_force_N", r.mean_f},
          {"sd_force_N", r.sd_f},
          {"impulse_Ns", {r.impulse.x(), r.impulse.y(), r.impulse.z()}},
          {"peak_speed_mps", r.peak_speed},
          {"peak_spin_radps", r.peak_spin},
          {"end_m", {r.end.x(), r.end.y(), r.end.z()}},
          {"end_yaw_rad", r.yaw},
          {"thrown", v.thrown},
          {"spun", v.spun}};
}

// The bars for a method other than the reference: nothing is thrown (every method); the
// proposed method and proxy-6dof at 1 ms meet the analytic expectations, follow the reference
// off centre and turn its way.
void AddChecks(Checks* checks, const std::string& name, const T37Result& r, const T37Result& ref,
               const T37Verdict& v) {
  checks->Add(fmt::format("{}_{}_not_thrown", name, r.method), !v.thrown, r.peak_speed,
              v.speed_bound);
  if (r.method == std::string("proxy-6dof@20ms")) return;
  if (r.rolling_radius > 0.0) {
    checks->Add(fmt::format("{}_{}_spin_within_2.5_v_over_r", name, r.method), !v.spun, r.peak_spin,
                *v.spin_bound);
  }
  if (v.slide_ok) {
    checks->Add(fmt::format("{}_{}_coulomb_within_5pc", name, r.method), *v.slide_ok,
                *v.slide_error, kSlideBar);
    // A steady slide feels steady: no more force fluctuation than the rigid tool's.
    checks->Add(fmt::format("{}_{}_force_sd_within_ref", name, r.method), r.sd_f <= ref.sd_f,
                r.sd_f, ref.sd_f);
  }
  if (v.force_vs_ref) {
    checks->Add(fmt::format("{}_{}_impulse_within_10pc_of_ref", name, r.method),
                std::abs(*v.force_vs_ref) <= kForceBar, *v.force_vs_ref, kForceBar);
  }
  if (v.pose_error) {
    checks->Add(fmt::format("{}_{}_position_within_2cm_of_ref", name, r.method),
                *v.pose_error <= kPoseBar, *v.pose_error, kPoseBar);
  }
  if (v.same_turn) checks->Add(fmt::format("{}_{}_turns_as_ref", name, r.method), *v.same_turn);
}

}  // namespace

int RunT37(const std::filesystem::path& out, bool quiet) {
  return RunT37(out, quiet, {});
}

int RunT37Full(const std::filesystem::path& out, bool quiet) {
  T37Options options;
  options.pointers = {"box", "sphere"};
  return RunT37(out, quiet, options);
}

int RunT37(const std::filesystem::path& out, bool quiet, const T37Options& options) {
  const std::vector<T37Result> results = RunT37Cases(out, quiet, options);
  const std::size_t per_case = std::size(kVariants);
  Table csv = CsvTable();
  Table md = MdTable();
  Checks checks;
  nlohmann::json summary;
  for (std::size_t i = 0; i < results.size(); i += per_case) {
    const T37Result& ref = results[i];
    const std::string name =
        fmt::format("{}_{}_{}", ref.shape, ref.pointer, ref.offcentre ? "offcentre" : "centred");
    for (std::size_t k = 0; k < per_case; ++k) {
      const T37Result& r = results[i + k];
      const T37Verdict v = Judge(r, ref);
      AddCsvRow(&csv, name, r, v);
      AddMdRow(&md, name, r, v, k);
      summary["cases"][name][r.method] = SummaryOf(r, v);
      if (k > 0) AddChecks(&checks, name, r, ref, v);
    }
  }
  WriteText(out / "t3_7.csv", csv.Csv());
  WriteText(out / "t3_7.md", md.Markdown());
  Plot(out, "t3_7", PlotScript(Cases(options)), quiet);
  summary["experiment"] = "t3.7";
  summary["machine"] = MachineTag();
  summary["window_s"] = {kFrom, kDuration};
  summary["reference"] = kVariants[0].label;
  if (!quiet) std::cout << md.Markdown() << "\n";
  return FinishExperiment(out, std::move(summary), checks, quiet);
}

}  // namespace mrh::experiments::internal
