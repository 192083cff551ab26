// SPDX-License-Identifier: Apache-2.0
// Summary statistics shared by the engine, the experiments and the benchmarks.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace mrh {

/// The p-th percentile (p in percent, 0–100) of `values` by the nearest-rank definition: the
/// smallest sample such that at least p % of the samples are ≤ it, i.e. the ⌈p/100 · N⌉-th
/// smallest (the smallest for p = 0, the largest for p = 100). Every p50/p99 this project
/// reports (summary.json, experiment tables, benchmark counters) uses it, so they compare.
/// Returns 0 for no samples. Takes `values` by value (it partially sorts the copy).
inline double Percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  const double rank =
      std::ceil(std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(values.size()));
  const std::size_t i =
      std::min(values.size() - 1, rank < 1.0 ? 0 : static_cast<std::size_t>(rank) - 1);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(i), values.end());
  return values[i];
}

}  // namespace mrh
