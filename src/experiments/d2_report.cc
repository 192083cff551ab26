// SPDX-License-Identifier: Apache-2.0
// Demo D2, articulated mechanisms: every case × run, the tables, the figure and the checks.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "d2_impl.h"
#include "experiment_table.h"
#include "experiment_util.h"
#include "mrh/core/error.h"

namespace mrh::experiments::internal {
namespace {

constexpr double kAnalyticTolerance = 0.05;  // drawer reference vs d v + F, relative

// One case × run: its metrics, or the error that ended it (a failed row, not a crash).
struct D2Row {
  std::optional<D2Metrics> metrics;
  std::string error;
};

struct D2Tables {
  Table csv{{"case", "method", "physics_dt_s", "mean_force_N", "mean_vs_reference", "sd_force_N",
             "sd_ratio", "contact_lost", "hinge_rms_deg", "slide_rms_mm", "result"}};
  Table md{{"case", "method", "mean abs(f) (N)", "vs ref.", "sd (N)", "sd ratio", "contact lost",
            "hinge RMS (deg)", "slide RMS (mm)", "result"}};
};

// Each case's runs, the reference first; a run that throws is kept as an error row.
std::vector<std::vector<D2Row>> RunAll(const std::filesystem::path& out, const D2Options& o,
                                       bool quiet) {
  std::vector<std::vector<D2Row>> rows;
  for (const D2Case& c : o.cases) {
    std::vector<D2Trace> traces;
    rows.emplace_back();
    for (const D2Method& m : o.runs) {
      if (!quiet) std::cout << "d2: " << c.name << " / " << m.Label() << "...\n";
      try {
        traces.push_back(RunD2Case(out, o, c, m));
      } catch (const Error& e) {
        traces.emplace_back();
        rows.back().push_back({std::nullopt, e.what()});
        continue;
      }
      rows.back().push_back({});
    }
    for (std::size_t mi = 0; mi < o.runs.size(); ++mi) {
      D2Row& row = rows.back()[mi];
      if (!row.error.empty() || !rows.back()[0].error.empty()) continue;
      row.metrics = AnalyzeD2(o, c, traces[mi], traces[0]);
    }
  }
  return rows;
}

std::string Result(const D2Method& m, bool reference, const std::optional<D2Bars>& bars) {
  if (reference) return "reference";
  if (!bars) return m.checked ? "FAIL (error)" : "error";
  if (!m.checked) return bars->all() ? "(pass)" : "(fail)";
  return bars->all() ? "PASS" : "FAIL";
}

// The row of a run that threw, or whose reference threw.
void AddErrorRow(const D2Case& c, const D2Method& m, const D2Row& row, const D2Row& ref,
                 bool reference, D2Tables* t, nlohmann::json* s) {
  const std::string why = row.error.empty() ? "reference failed: " + ref.error : row.error;
  *s = {{"error", why}, {"meets_bars", false}};
  const std::string result = Result(m, reference, std::nullopt);
  t->csv.Add(
      {c.name, m.Label(), fmt::format("{:g}", m.physics_dt), "", "", "", "", "", "", "", result});
  t->md.Add({c.name, m.Label(), "", "", "", "", "", "", "", result + ": " + why});
}

nlohmann::json RowJson(const D2Method& m, const D2Metrics& r, double rel, double sd_ratio,
                       const D2Bars& b) {
  return {
      {"physics_dt_s", m.physics_dt},
      {"mean_force_N", r.mean_force},
      {"mean_vs_reference", rel},
      {"sd_force_N", r.sd_force},
      {"sd_ratio", sd_ratio},
      {"contact_lost", r.contact_lost},
      {"hinge_rms_deg", r.hinge_rms_deg},
      {"slide_rms_mm", r.slide_rms_mm},
      {"steady_force_N", r.steady_force},
      {"bars", {{"mean", b.mean}, {"sd", b.sd}, {"contact_lost", b.lost}, {"joints", b.joints}}},
      {"meets_bars", b.all()}};
}

// One table row and its summary entry; returns the bars (none if the run or reference failed).
std::optional<D2Bars> AddRow(const D2Case& c, const D2Method& m, const D2Row& row, const D2Row& ref,
                             bool reference, D2Tables* t, nlohmann::json* summary) {
  nlohmann::json& s = (*summary)["cases"][c.name][m.Label()];
  if (!row.metrics || !ref.metrics) {
    AddErrorRow(c, m, row, ref, reference, t, &s);
    return std::nullopt;
  }
  const D2Metrics& r = *row.metrics;
  const D2Metrics& f = *ref.metrics;
  const D2Bars b = D2Check(r, f);
  const double rel = f.mean_force > 0.0 ? r.mean_force / f.mean_force - 1.0 : 0.0;
  const double sd_ratio = f.sd_force > 0.0 ? r.sd_force / f.sd_force : 0.0;
  const std::string result = Result(m, reference, b);
  t->csv.AddFormatted("{},{},{:g},{:.4f},{:.4f},{:.4f},{:.3f},{:.4f},{:.3f},{:.3f},{}", c.name,
                      m.Label(), m.physics_dt, r.mean_force, rel, r.sd_force, sd_ratio,
                      r.contact_lost, r.hinge_rms_deg, r.slide_rms_mm, result);
  t->md.Add({c.name, m.Label(), fmt::format("{:.3f}", r.mean_force),
             fmt::format("{:+.1f} %", 100 * rel), fmt::format("{:.3f}", r.sd_force),
             fmt::format("{:.2f}", sd_ratio), fmt::format("{:.1f} %", 100 * r.contact_lost),
             fmt::format("{:.2f}", r.hinge_rms_deg), fmt::format("{:.2f}", r.slide_rms_mm),
             result});
  s = RowJson(m, r, rel, sd_ratio, b);
  return b;
}

// The drawer's steady force per run against d v + F; the reference is checked.
std::string AnalyticTable(const D2Options& o, const D2Case& c, const std::vector<D2Row>& rows,
                          Checks* checks, nlohmann::json* summary) {
  const double analytic = D2AnalyticForce(c, o.speed);
  Table md({"case", "method", "steady abs(f) (N)", "d v + F (N)", "error"});
  for (std::size_t mi = 0; mi < o.runs.size(); ++mi) {
    const std::optional<D2Metrics>& r = rows[mi].metrics;
    const double rel = r ? r->steady_force / analytic - 1.0 : NAN;
    md.Add({c.name, o.runs[mi].Label(), r ? fmt::format("{:.4f}", r->steady_force) : "error",
            fmt::format("{:.4f}", analytic), fmt::format("{:+.2f} %", 100 * rel)});
    (*summary)["analytic"][c.name][o.runs[mi].Label()] = {
        {"steady_force_N", r ? r->steady_force : NAN},
        {"analytic_N", analytic},
        {"relative_error", rel}};
    if (mi == 0) {
      checks->Add(c.name + "_reference_matches_dv_plus_F", std::abs(rel) <= kAnalyticTolerance,
                  std::abs(rel), kAnalyticTolerance);
    }
  }
  return fmt::format(
      "\nSteady push ({:.1f} s after the touch to the push's end) vs the analytic d v + F at "
      "v = {:g} m/s:\n\n{}",
      o.steady_from, o.speed, md.Markdown());
}

// d2.png: per case, |f| vs t of every run, and every joint of every run vs t (colour: joint;
// dashes: run).
std::string D2Script(const D2Options& o) {
  std::string gp = fmt::format(
      "# d2: |f|(t) and joints(t) per mechanism and method. gnuplot d2.gp\n"
      "set terminal pngcairo size 1400,{} enhanced font ',9'\nset output 'd2.png'\n"
      "set datafile separator ','\nset grid\nset key top left\nset xlabel 't (s)'\n"
      "set multiplot layout {},2\n",
      330 * o.cases.size(), o.cases.size());
  for (const D2Case& c : o.cases) {
    gp += "set title '" + c.name + ": rendered |f| (N)'\nplot ";
    for (std::size_t i = 0; i < o.runs.size(); ++i) {
      gp += fmt::format("{}'runs/{}_{}_force.csv' using 1:2 with lines title '{}'", i ? ", " : "",
                        c.name, Slug(o.runs[i].Label(), '_'), o.runs[i].Label());
    }
    gp += "\nset title '" + c.name + ": joints (deg; slides mm)'\nplot ";
    for (std::size_t i = 0; i < o.runs.size(); ++i) {
      for (std::size_t k = 0; k < c.joints.size(); ++k) {
        gp +=
            fmt::format("{}'runs/{}_{}_joints.csv' using 1:{} with lines lc {} dt {} title '{} {}'",
                        i + k ? ", " : "", c.name, Slug(o.runs[i].Label(), '_'), k + 2, k + 1,
                        i + 1, c.joints[k].name, o.runs[i].Label());
      }
    }
    gp += "\n";
  }
  return gp + "unset multiplot\n";
}

}  // namespace

int RunD2(const std::filesystem::path& out, bool quiet) {
  return RunD2(out, quiet, DefaultD2Options());
}

int RunD2Full(const std::filesystem::path& out, bool quiet) {
  return RunD2(out, quiet, FullD2Options());
}

int RunD2(const std::filesystem::path& out, bool quiet, const D2Options& o) {
  std::filesystem::create_directories(out);
  const auto rows = RunAll(out, o, quiet);
  nlohmann::json summary;
  D2Tables tables;
  Checks checks;
  std::string analytic;
  for (std::size_t ci = 0; ci < o.cases.size(); ++ci) {
    const D2Case& c = o.cases[ci];
    for (std::size_t mi = 0; mi < o.runs.size(); ++mi) {
      const auto bars =
          AddRow(c, o.runs[mi], rows[ci][mi], rows[ci][0], mi == 0, &tables, &summary);
      if (mi > 0 && o.runs[mi].checked) {
        checks.Add(c.name + "_" + Slug(o.runs[mi].Label(), '_') + "_meets_bars",
                   bars && bars->all());
      }
    }
    if (c.frictionloss > 0.0 || c.damping > 0.0)
      analytic += AnalyticTable(o, c, rows[ci], &checks, &summary);
  }
  WriteText(out / "d2.csv", tables.csv.Csv());
  const std::string md =
      "# D2: articulated mechanisms, 20 ms local methods vs single-rate at 1 ms\n\n" +
      tables.md.Markdown() + analytic + "\nChecks:\n\n" + checks.Markdown();
  WriteText(out / "d2.md", md);
  Plot(out, "d2", D2Script(o), quiet);
  summary["experiment"] = "d2";
  summary["machine"] = MachineTag();
  summary["speed_mps"] = o.speed;
  summary["window_s_after_touch"] = {o.settle, "push end"};
  if (!quiet) std::cout << tables.md.Markdown() << analytic;
  return FinishExperiment(out, std::move(summary), checks, quiet);
}

}  // namespace mrh::experiments::internal
