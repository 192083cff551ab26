// SPDX-License-Identifier: Apache-2.0
// `mrh validate`, `mrh methods`, `mrh devices` and `mrh experiment`, plus the shared --set
// option.
#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "mrh/core/error.h"
#include "mrh/engine/engine.h"
#include "mrh/engine/method.h"
#include "mrh/experiments/experiments.h"
#include "mrh/psychophysics/study.h"
#include "mrh/session/devices.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::cli {
namespace {

namespace fs = std::filesystem;

constexpr const char* kValidateFooter =
    R"(Checks the session keys and values, loads the scene, builds the device and the
engine (method, pointer body and radius), then prints one line; nothing is run or written.

Examples:
  mrh validate session.json
  mrh validate session.json --set method=single-rate
)";

constexpr const char* kMethodsFooter = R"(Examples:
  mrh methods
  mrh run session.json --method single-rate
)";

constexpr const char* kDevicesFooter = R"(Examples:
  mrh devices
  mrh run session.json --set 'device={"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0]}'
)";

constexpr const char* kExperimentFooter = R"(Examples:
  mrh experiment --list
  mrh experiment NAME --out out/NAME
)";

void PrintTable(const std::vector<std::pair<std::string, std::string>>& rows) {
  std::size_t width = 0;
  for (const auto& row : rows) width = std::max(width, row.first.size());
  for (const auto& [name, summary] : rows) fmt::print("  {:<{}}  {}\n", name, width, summary);
}

}  // namespace

void AddSetOption(CLI::App& command, std::vector<std::string>* sets) {
  command
      .add_option("--set", *sets,
                  "Override a session key (repeatable); VALUE is JSON, else a string")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
}

CLI::App* AddValidateCommand(CLI::App& app, ValidateOptions* o) {
  CLI::App* validate =
      app.add_subcommand("validate", "Check a session file and its scene without running anything");
  validate->add_option("SESSION", o->session, "Session file (JSON)")
      ->required()
      ->check(CLI::ExistingFile);
  AddSetOption(*validate, &o->sets);
  validate->footer(kValidateFooter);
  return validate;
}

CLI::App* AddMethodsCommand(CLI::App& app) {
  CLI::App* methods = app.add_subcommand("methods", "List the haptic rendering methods");
  methods->footer(kMethodsFooter);
  return methods;
}

CLI::App* AddDevicesCommand(CLI::App& app) {
  CLI::App* devices = app.add_subcommand("devices", "List the device types (session device.type)");
  devices->footer(kDevicesFooter);
  return devices;
}

CLI::App* AddExperimentCommand(CLI::App& app, ExperimentOptions* o) {
  CLI::App* experiment = app.add_subcommand(
      "experiment", "Run a reproducible experiment by name (CSV, summary and plots in --out)");
  experiment->add_option("NAME", o->name, "Experiment name (see --list)");
  experiment->add_option("--out,-o", o->out, "Output folder (default: out/<name>)")
      ->type_name("DIR");
  experiment->add_flag("--list", o->list, "List the experiments and exit");
  experiment->add_flag("--quiet,-q", o->quiet, "Suppress progress output");
  experiment->add_flag("--full", o->full,
                       "Run the big sweep (slow; e.g. t4.3 up to 1000 cubes) instead of the fast "
                       "default");
  experiment->footer(kExperimentFooter);
  return experiment;
}

// A session's `psychophysics` object (in the file or from --set) is read only by `mrh
// psychophysics run`; `mrh validate` and `mrh run` check it too, so that all three accept the same
// files.
void CheckStudy(const fs::path& session, const std::vector<std::string>& sets) {
  bool has_study = false;
  for (const std::string& set : sets) has_study = has_study || set.rfind("psychophysics", 0) == 0;
  if (!has_study) {
    std::ifstream in(session, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const nlohmann::json json = nlohmann::json::parse(text, nullptr, false);
    has_study = json.is_object() && json.contains("psychophysics");
  }
  if (has_study) psychophysics::LoadStudy(session, sets);
}

// Building the engine (not only the world and device) also checks the method name and the
// pointer body and radius, which is what a user validating a session wants to know.
int ValidateCommand(const ValidateOptions& o) {
  const session::Session s = session::LoadSession(o.session, o.sets);
  const std::unique_ptr<engine::Engine> engine = session::MakeEngine(s);
  CheckStudy(o.session, o.sets);
  const int bodies = engine->world().num_bodies() - 1;  // without the world body
  for (const std::string& warning : engine->world().LoadWarnings()) {
    fmt::print(stderr, "mrh: warning: {}\n", warning);
  }
  for (const std::string& warning : engine->setup_warnings()) {
    fmt::print(stderr, "mrh: warning: {}\n", warning);
  }
  fmt::print("ok: {} (method {}, scene {}, {} bodies)\n", o.session.string(), s.engine.method,
             s.scene.lexically_proximate(fs::current_path()).string(), bodies);
  return kExitOk;
}

int MethodsCommand() {
  PrintTable(engine::ListMethods());
  return kExitOk;
}

int DevicesCommand() {
  std::vector<std::pair<std::string, std::string>> rows;
  for (const session::DeviceDescriptor& d : session::DeviceDescriptors()) {
    rows.emplace_back(d.name, d.summary);
  }
  PrintTable(rows);
  return kExitOk;
}

int ExperimentCommand(const ExperimentOptions& o) {
  if (o.list) {
    PrintTable(experiments::List());
    return kExitOk;
  }
  if (o.name.empty()) {
    throw InvalidArgument(
        "experiment: no NAME given; expected an experiment name (see `mrh experiment --list`)");
  }
  const fs::path out = o.out.empty() ? fs::path("out") / o.name : o.out;
  return experiments::Run(o.name, fs::absolute(out).lexically_normal(), o.quiet, o.full);
}

}  // namespace mrh::cli
