// SPDX-License-Identifier: Apache-2.0
// The `psychophysics` session object (parse + validate), the seed and the trial schedule.
#include "mrh/psychophysics/study.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>

#include "mrh/core/error.h"
#include "mrh/engine/method.h"
#include "session/json_node.h"
#include "session/json_text.h"
#include "session/overrides.h"

namespace mrh::psychophysics {
namespace {

using nlohmann::json;

constexpr const char* kKeys[] = {"standard_method",   "standard_mass", "masses", "methods",
                                 "trials_per_mass",   "speed",         "seed",   "geom",
                                 "stimulus_duration", "pause"};

// Errors name the file and the dotted key: "s.json: psychophysics.masses[1] = -3; expected ...".
class Block {
 public:
  Block(std::string origin, const json& object) : origin_(std::move(origin)), object_(object) {}

  [[noreturn]] void Fail(const std::string& key, const json& value,
                         const std::string& expected) const {
    throw InvalidArgument(fmt::format("{}: psychophysics.{} = {}; expected {}", origin_, key,
                                      value.dump(), expected));
  }

  double Number(const char* key, double fallback) const {
    if (!object_.contains(key)) return fallback;
    const json& v = object_.at(key);
    if (!v.is_number()) Fail(key, v, "a number");
    return v.get<double>();
  }

  std::string Text(const char* key, const std::string& fallback) const {
    if (!object_.contains(key)) return fallback;
    const json& v = object_.at(key);
    if (!v.is_string()) Fail(key, v, "a string");
    return v.get<std::string>();
  }

  template <typename T>
  std::vector<T> List(const char* key, const std::vector<T>& fallback, const char* what) const {
    if (!object_.contains(key)) return fallback;
    const json& v = object_.at(key);
    if (!v.is_array() || v.empty()) Fail(key, v, fmt::format("a non-empty array of {}", what));
    std::vector<T> out;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const bool ok = std::is_same_v<T, double> ? v[i].is_number() : v[i].is_string();
      if (!ok) Fail(fmt::format("{}[{}]", key, i), v[i], what);
      out.push_back(v[i].get<T>());
    }
    return out;
  }

  const json& object() const { return object_; }

 private:
  std::string origin_;
  const json& object_;
};

StudySettings ParseSettings(const Block& b) {
  for (const auto& [key, value] : b.object().items()) {
    if (std::find_if(std::begin(kKeys), std::end(kKeys), [&](const char* k) {
          return key == k;
        }) == std::end(kKeys)) {
      b.Fail(key, value,
             "no such key; known: standard_method, standard_mass, masses, methods, "
             "trials_per_mass, speed, seed, geom, stimulus_duration, pause");
    }
  }
  StudySettings s;
  s.standard_method = b.Text("standard_method", s.standard_method);
  s.standard_mass = b.Number("standard_mass", s.standard_mass);
  s.masses = b.List<double>("masses", s.masses, "masses in kg");
  s.methods = b.List<std::string>("methods", s.methods, "method names");
  if (b.object().contains("trials_per_mass")) {
    const json& v = b.object().at("trials_per_mass");
    if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > 100000) {
      b.Fail("trials_per_mass", v, "an integer in [1, 100000]");
    }
    s.trials_per_mass = v.get<int>();
  }
  s.speed = b.Number("speed", s.speed);
  if (b.object().contains("seed")) {
    const json& v = b.object().at("seed");
    if (!v.is_number_unsigned()) b.Fail("seed", v, "an unsigned integer");
    s.seed = v.get<std::uint64_t>();
  }
  s.geom = b.Text("geom", s.geom);
  s.stimulus_duration = b.Number("stimulus_duration", s.stimulus_duration);
  s.pause = b.Number("pause", s.pause);
  return s;
}

void ExpectPositive(double value, const char* key, const char* unit) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw InvalidArgument(
        fmt::format("psychophysics.{} = {}; expected a finite value > 0 {}", key, value, unit));
  }
}

void ExpectMethod(const std::string& method, const std::string& key) {
  std::string known;
  for (const auto& [name, summary] : engine::ListMethods()) {
    if (name == method) return;
    known += (known.empty() ? "" : ", ") + name;
  }
  throw InvalidArgument(
      fmt::format("psychophysics.{} = \"{}\"; expected one of: {}", key, method, known));
}

}  // namespace

void StudySettings::Validate() const {
  ExpectMethod(standard_method, "standard_method");
  ExpectPositive(standard_mass, "standard_mass", "kg");
  for (std::size_t i = 0; i < masses.size(); ++i) {
    ExpectPositive(masses[i], fmt::format("masses[{}]", i).c_str(), "kg");
  }
  if (masses.empty() || std::set<double>(masses.begin(), masses.end()).size() != masses.size()) {
    throw InvalidArgument("psychophysics.masses: expected a non-empty list of distinct masses");
  }
  for (std::size_t i = 0; i < methods.size(); ++i) {
    ExpectMethod(methods[i], fmt::format("methods[{}]", i));
  }
  if (methods.empty() ||
      std::set<std::string>(methods.begin(), methods.end()).size() != methods.size()) {
    throw InvalidArgument("psychophysics.methods: expected a non-empty list of distinct methods");
  }
  if (trials_per_mass < 1) {
    throw InvalidArgument(
        fmt::format("psychophysics.trials_per_mass = {}; expected >= 1", trials_per_mass));
  }
  ExpectPositive(speed, "speed", "m/s");
  ExpectPositive(stimulus_duration, "stimulus_duration", "s");
  if (!(std::isfinite(pause) && pause >= 0.0)) {
    throw InvalidArgument(fmt::format("psychophysics.pause = {}; expected >= 0 s", pause));
  }
  if (geom.empty()) throw InvalidArgument("psychophysics.geom = \"\"; expected a geom name");
}

Study LoadStudy(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  Study study{.base = session::LoadSession(file, overrides), .settings = {}};
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  // The same `--set` overrides reach the psychophysics object (psychophysics.pause=0, ...).
  json document = session::internal::ParseJsonText(text.str(), file.string());
  session::internal::Context context(file.string(), std::filesystem::absolute(file).parent_path());
  session::internal::ApplyOverrides(overrides, &document, &context);
  if (!document.contains("psychophysics") || !document.at("psychophysics").is_object()) {
    throw InvalidArgument(fmt::format(
        "{}: psychophysics = {}; expected an object with the study's settings (see "
        "docs/psychophysics.md)",
        file.string(),
        document.contains("psychophysics") ? document["psychophysics"].dump() : "(missing)"));
  }
  study.settings = ParseSettings(Block(file.string(), document.at("psychophysics")));
  try {
    study.settings.Validate();
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(fmt::format("{}: {}", file.string(), e.what()));
  }
  return study;
}

std::uint64_t StudySeed(const StudySettings& settings, const std::string& subject) {
  if (settings.seed) return *settings.seed;
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bit
  for (const unsigned char c : subject) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

std::vector<Trial> MakeSchedule(const StudySettings& settings, std::uint64_t seed) {
  std::vector<Trial> trials;
  for (const std::string& method : settings.methods) {
    for (const double mass : settings.masses) {
      for (int r = 0; r < settings.trials_per_mass; ++r) {
        trials.push_back(Trial{.method = method,
                               .comparison_mass = mass,
                               .comparison_first = 2 * r < settings.trials_per_mass});
      }
    }
  }
  // Fisher–Yates with a modulo draw: the bias, < n / 2^64, is far below anything measurable.
  std::mt19937_64 rng(seed);
  for (std::size_t i = trials.size(); i > 1; --i) {
    std::swap(trials[i - 1], trials[rng() % i]);
  }
  for (std::size_t i = 0; i < trials.size(); ++i) trials[i].index = static_cast<int>(i);
  return trials;
}

}  // namespace mrh::psychophysics
