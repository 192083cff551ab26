// SPDX-License-Identifier: Apache-2.0
// `mrh psychophysics analyze`: per (subject, method) fits of trials files, tables and curves.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "mrh/psychophysics/logistic_fit.h"
#include "mrh/psychophysics/trials.h"

namespace mrh::psychophysics {

/// One (subject, comparison method) cell of table 4.4.
struct SubjectFit {
  std::string subject;
  std::string method;
  std::vector<Observation> data;  ///< per comparison mass, ascending
  PsychometricFit fit;
};

/// Groups the rows by (subject, method), in order of first appearance, and fits each.
/// @throws mrh::InvalidArgument if one group mixes standard masses (its PSE test would have no
/// single reference).
std::vector<SubjectFit> FitAll(const std::vector<TrialRow>& rows);

/// Mean PSE per method over the fitted subjects (unfittable ones are left out and counted).
struct MethodMean {
  std::string method;
  double mean_pse = 0.0;  ///< kg; 0 when fitted == 0
  int fitted = 0;
  int unfitted = 0;
};

std::vector<MethodMean> MeansByMethod(const std::vector<SubjectFit>& fits);

/// Writes into `out` (created): psychometric.json ({"fits": [{"subject", "method",
/// "standard_mass", "trials", "theta1", "theta2", "pse", "pse_sd", "chi2", "p"}]}, with null
/// estimates for a fit that does not exist), pse_table.md and pse_table.csv (table 4.4: PSE per
/// subject and method, the fit status, the mean per method), curves.csv / points.csv and
/// curves.gp, and runs gnuplot for curves.png (figs. 4.14-4.15). Returns false with the reason
/// in *why if only the plot could not be drawn.
/// @throws mrh::RuntimeError on I/O failure.
bool WriteAnalysis(const std::filesystem::path& out, const std::vector<SubjectFit>& fits,
                   std::string* why);

/// The Markdown table of WriteAnalysis (pse_table.md).
std::string PseTableMarkdown(const std::vector<SubjectFit>& fits);

}  // namespace mrh::psychophysics
