// SPDX-License-Identifier: Apache-2.0
// Grouping trials into fits, and the result files: JSON, table 4.4, psychometric curves.
#include "mrh/psychophysics/analysis.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "mrh/core/error.h"
#include "mrh/report/report.h"

namespace mrh::psychophysics {
namespace {

// Points drawn per psychometric curve.
constexpr int kCurvePoints = 200;

void Write(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out.flush()) throw RuntimeError(fmt::format("cannot write {}", file.string()));
}

nlohmann::json Estimate(const PsychometricFit& f, double value) {
  return f.status == FitStatus::kOk ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json FitsJson(const std::vector<SubjectFit>& fits) {
  nlohmann::json list = nlohmann::json::array();
  for (const SubjectFit& s : fits) {
    const PsychometricFit& f = s.fit;
    list.push_back({{"subject", s.subject},
                    {"method", s.method},
                    {"standard_mass", f.standard_mass},
                    {"trials", f.trials},
                    {"theta1", Estimate(f, f.theta1)},
                    {"theta2", Estimate(f, f.theta2)},
                    {"pse", Estimate(f, f.pse)},
                    {"pse_sd", Estimate(f, f.pse_sd)},
                    {"chi2", Estimate(f, f.chi2)},
                    {"p", Estimate(f, f.p)}});
  }
  return {{"fits", list}};
}

std::string TableCsv(const std::vector<SubjectFit>& fits) {
  std::string csv = "subject,method,standard_mass,trials,status,theta1,theta2,pse,pse_sd,chi2,p\n";
  for (const SubjectFit& s : fits) {
    const PsychometricFit& f = s.fit;
    if (f.status == FitStatus::kOk) {
      csv += fmt::format("{},{},{},{},ok,{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n",
                         s.subject, s.method, f.standard_mass, f.trials, f.theta1, f.theta2, f.pse,
                         f.pse_sd, f.chi2, f.p);
    } else {
      csv += fmt::format("{},{},{},{},{},,,,,,\n", s.subject, s.method, f.standard_mass, f.trials,
                         FitStatusName(f.status));
    }
  }
  for (const MethodMean& m : MeansByMethod(fits)) {
    csv += fmt::format("mean,{},,,{} fitted,,,{},,,\n", m.method, m.fitted,
                       m.fitted > 0 ? fmt::format("{:.17g}", m.mean_pse) : "");
  }
  return csv;
}

// curves.csv: mass, then P per fitted (subject, method); points.csv: mass, fraction, column.
void WriteCurves(const std::filesystem::path& out, const std::vector<SubjectFit>& fits) {
  double lo = 1e300, hi = -1e300;
  for (const SubjectFit& s : fits) {
    for (const Observation& o : s.data) lo = std::min(lo, o.mass), hi = std::max(hi, o.mass);
  }
  if (lo > hi) lo = 0.0, hi = 1.0;
  std::string curves = "mass";
  for (const SubjectFit& s : fits) curves += fmt::format(",{} {}", s.subject, s.method);
  curves += "\n";
  for (int i = 0; i <= kCurvePoints; ++i) {
    const double m = lo + (hi - lo) * i / kCurvePoints;
    curves += fmt::format("{:.6g}", m);
    for (const SubjectFit& s : fits) {
      const PsychometricFit& f = s.fit;
      if (f.status != FitStatus::kOk) {
        curves += ",";
        continue;
      }
      curves += fmt::format(",{:.6g}", 1.0 / (1.0 + std::exp(-(f.theta1 + f.theta2 * m))));
    }
    curves += "\n";
  }
  Write(out / "curves.csv", curves);
  std::string points = "index,subject,method,mass,fraction,n\n";
  for (std::size_t k = 0; k < fits.size(); ++k) {
    for (const Observation& o : fits[k].data) {
      points += fmt::format("{},{},{},{},{:.6g},{}\n", k, fits[k].subject, fits[k].method, o.mass,
                            o.n > 0 ? static_cast<double>(o.yes) / o.n : 0.0, o.n);
    }
  }
  Write(out / "points.csv", points);
}

// One panel per method (figs. 4.14 and 4.15): every subject's curve and its data points.
std::string CurvesScript(const std::vector<SubjectFit>& fits) {
  std::vector<std::string> methods;
  for (const SubjectFit& s : fits) {
    if (std::find(methods.begin(), methods.end(), s.method) == methods.end()) {
      methods.push_back(s.method);
    }
  }
  std::string gp = fmt::format(
      "# Psychometric curves (thesis figs. 4.14-4.15). Re-run with: gnuplot curves.gp\n"
      "set terminal pngcairo size {},500 enhanced font ',11'\nset output 'curves.png'\n"
      "set datafile separator ','\nset grid\nset yrange [-0.05:1.05]\nset key bottom right\n"
      "set xlabel 'comparison mass (kg)'\nset ylabel 'P(comparison heavier)'\n"
      "set multiplot layout 1,{}\n",
      std::max<std::size_t>(1, methods.size()) * 600, std::max<std::size_t>(1, methods.size()));
  for (const std::string& method : methods) {
    gp += fmt::format("set title '{}'\nplot ", method);
    bool first = true;
    for (std::size_t k = 0; k < fits.size(); ++k) {
      if (fits[k].method != method) continue;
      const std::string sep = first ? "" : ", ";
      first = false;
      gp += fmt::format(
          "{}'curves.csv' using 1:{} with lines lw 2 lc {} title '{}', 'points.csv' using "
          "($1=={} ? $4 : 1/0):5 with points pt 7 lc {} notitle",
          sep, k + 2, k % 8 + 1, fits[k].subject, k, k % 8 + 1);
    }
    gp += "\n";
  }
  return gp + "unset multiplot\n";
}

}  // namespace

std::vector<SubjectFit> FitAll(const std::vector<TrialRow>& rows) {
  std::vector<SubjectFit> fits;
  std::vector<std::map<double, Observation>> cells;
  std::vector<double> standards;
  for (const TrialRow& r : rows) {
    auto it = std::find_if(fits.begin(), fits.end(), [&](const SubjectFit& f) {
      return f.subject == r.subject && f.method == r.method;
    });
    const std::size_t k = static_cast<std::size_t>(it - fits.begin());
    if (it == fits.end()) {
      fits.push_back(SubjectFit{.subject = r.subject, .method = r.method, .data = {}, .fit = {}});
      cells.emplace_back();
      standards.push_back(r.standard_mass);
    }
    if (standards[k] != r.standard_mass) {
      throw InvalidArgument(fmt::format(
          "trials of subject \"{}\", method \"{}\": standard_mass {} and {} kg; expected one "
          "standard per subject and method",
          r.subject, r.method, standards[k], r.standard_mass));
    }
    Observation& o = cells[k][r.comparison_mass];
    o.mass = r.comparison_mass;
    ++o.n;
    o.yes += r.comparison_heavier ? 1 : 0;
  }
  for (std::size_t k = 0; k < fits.size(); ++k) {
    for (const auto& [mass, o] : cells[k]) fits[k].data.push_back(o);
    fits[k].fit = FitLogistic(fits[k].data, standards[k]);
  }
  return fits;
}

std::vector<MethodMean> MeansByMethod(const std::vector<SubjectFit>& fits) {
  std::vector<MethodMean> means;
  for (const SubjectFit& s : fits) {
    auto it = std::find_if(means.begin(), means.end(), [&](const MethodMean& m) {
      return m.method == s.method;
    });
    if (it == means.end()) it = means.insert(means.end(), MethodMean{.method = s.method});
    if (s.fit.status == FitStatus::kOk) {
      it->mean_pse += s.fit.pse;
      ++it->fitted;
    } else {
      ++it->unfitted;
    }
  }
  for (MethodMean& m : means) m.mean_pse = m.fitted > 0 ? m.mean_pse / m.fitted : 0.0;
  return means;
}

std::string PseTableMarkdown(const std::vector<SubjectFit>& fits) {
  std::string md =
      "| subject | method | trials | PSE (kg) | SD (kg) | chi2 | p | fit |\n"
      "|---|---|---|---|---|---|---|---|\n";
  for (const SubjectFit& s : fits) {
    const PsychometricFit& f = s.fit;
    if (f.status == FitStatus::kOk) {
      md += fmt::format("| {} | {} | {} | {:.1f} | {:.1f} | {:.3g} | {:.3g} | ok |\n", s.subject,
                        s.method, f.trials, f.pse, f.pse_sd, f.chi2, f.p);
    } else {
      md += fmt::format("| {} | {} | {} | - | - | - | - | {} |\n", s.subject, s.method, f.trials,
                        FitStatusName(f.status));
    }
  }
  for (const MethodMean& m : MeansByMethod(fits)) {
    md += fmt::format("| **mean** | {} | | {} | | | | {} of {} fitted |\n", m.method,
                      m.fitted > 0 ? fmt::format("**{:.1f}**", m.mean_pse) : "-", m.fitted,
                      m.fitted + m.unfitted);
  }
  return md;
}

bool WriteAnalysis(const std::filesystem::path& out, const std::vector<SubjectFit>& fits,
                   std::string* why) {
  std::filesystem::create_directories(out);
  Write(out / "psychometric.json", FitsJson(fits).dump(2) + "\n");
  Write(out / "pse_table.md", PseTableMarkdown(fits));
  Write(out / "pse_table.csv", TableCsv(fits));
  WriteCurves(out, fits);
  Write(out / "curves.gp", CurvesScript(fits));
  return report::RunGnuplotScript(out, "curves.gp", "curves.png", why);
}

}  // namespace mrh::psychophysics
