// SPDX-License-Identifier: Apache-2.0
// The experiment registry: names → drivers.
#include "mrh/experiments/experiments.h"

#include <fmt/format.h>

#include "experiments_impl.h"
#include "mrh/core/error.h"

namespace mrh::experiments {
namespace {

struct Entry {
  const char* name;
  const char* summary;
  int (*run)(const std::filesystem::path&, bool);
};

constexpr Entry kExperiments[] = {
    {"t4.1", "impulse delivered to a moving 60 kg cube: single-rate vs impulse (fig. 4.13)",
     internal::RunT41},
};

}  // namespace

int Run(const std::string& name, const std::filesystem::path& out, bool quiet) {
  for (const Entry& e : kExperiments) {
    if (name == e.name) return e.run(out, quiet);
  }
  std::string known;
  for (const Entry& e : kExperiments) known += (known.empty() ? "" : ", ") + std::string(e.name);
  throw InvalidArgument(fmt::format("experiment '{}' is unknown; expected one of: {}", name, known));
}

std::vector<std::pair<std::string, std::string>> List() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const Entry& e : kExperiments) out.emplace_back(e.name, e.summary);
  return out;
}

}  // namespace mrh::experiments
