// SPDX-License-Identifier: Apache-2.0
// The mrh command line: parses the subcommand, runs it, and maps errors to one line + exit code.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <optional>
#include <string_view>

#include "commands.h"
#include "mrh/core/error.h"
#include "psychophysics_command.h"

namespace mrh::cli {
namespace {

// Kept equal to project(VERSION) in the top-level CMakeLists.txt.
constexpr const char* kVersion = "0.1.0";

constexpr const char* kRootFooter = R"(Examples:
  mrh run session.json                       run a session, results in out/session-<method>/
  mrh run session.json --method single-rate  same scene with the single-rate baseline
  mrh run session.json --mode realtime --duration 5
  mrh validate session.json                  check a session and its scene
  mrh methods                                list the rendering methods
  mrh devices                                list the device types
  mrh experiment --list                      list the reproducible experiments
  mrh ir session.json --pose 0 0 0.1 1 0 0 0 print the contact IR at a pointer pose (JSON)
  mrh view session.json                      open the interactive viewer
  mrh psychophysics run s.json --subject A --out DIR   a 2AFC study (docs/psychophysics.md)

Run `mrh <command> --help` for the options of a command.

Exit codes:
  0  success
  1  runtime error (I/O failure, unrecoverable physics failure)
  2  bad input (session file, scene, or command-line flags)
)";

constexpr const char* kSeeHelp = "Run with --help for more information.";

// Error messages are one line by contract; a library message with a line break (e.g. from a
// parser) is folded rather than printed as a multi-line dump.
std::string OneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

int Fail(int code, const std::string& message, bool see_help = false) {
  fmt::print(stderr, "mrh: error: {}\n", OneLine(message));
  if (see_help) fmt::print(stderr, "{}\n", kSeeHelp);
  return code;
}

// CLI11 reports an unknown first word as a missing subcommand; name the word instead.
std::optional<std::string> UnknownCommand(const CLI::App& app, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg.starts_with('-')) continue;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) {
           return true;
         })) {
      if (sub->check_name(std::string(arg))) return std::nullopt;
    }
    return std::string(arg);
  }
  return std::nullopt;
}

struct Options {
  RunOptions run;
  ValidateOptions validate;
  ExperimentOptions experiment;
  IrOptions ir;
  ViewOptions view;
  PsychophysicsOptions psychophysics;
};

struct Commands {
  const CLI::App* run;
  const CLI::App* validate;
  const CLI::App* methods;
  const CLI::App* devices;
  const CLI::App* ir;
  const CLI::App* view;
  PsychophysicsCommands psychophysics;
};

int Dispatch(const CLI::App& app, const Options& o, const Commands& c) {
  if (app.got_subcommand(c.run)) return RunCommand(o.run);
  if (app.got_subcommand(c.validate)) return ValidateCommand(o.validate);
  if (app.got_subcommand(c.methods)) return MethodsCommand();
  if (app.got_subcommand(c.devices)) return DevicesCommand();
  if (app.got_subcommand(c.ir)) return IrCommand(o.ir);
  if (app.got_subcommand(c.view)) return ViewCommand(o.view);
  if (app.got_subcommand(c.psychophysics.top)) {
    return PsychophysicsCommand(c.psychophysics, o.psychophysics);
  }
  return ExperimentCommand(o.experiment);
}

int Main(int argc, char** argv) {
  CLI::App app(
      "mrh: multi-rate haptic rendering. Runs a session (a scene, a rendering method, a "
      "simulated or real device), validates session files, lists the rendering methods "
      "and reproduces the experiments.",
      "mrh");
  app.set_version_flag("--version", fmt::format("mrh {}", kVersion));
  app.require_subcommand(1);
  app.footer(kRootFooter);
  Options o;
  Commands c{};
  c.run = AddRunCommand(app, &o.run);
  c.validate = AddValidateCommand(app, &o.validate);
  c.methods = AddMethodsCommand(app);
  c.devices = AddDevicesCommand(app);
  AddExperimentCommand(app, &o.experiment);
  c.ir = AddIrCommand(app, &o.ir);
  c.view = AddViewCommand(app, &o.view);
  c.psychophysics = AddPsychophysicsCommand(app, &o.psychophysics);

  if (const std::optional<std::string> word = UnknownCommand(app, argc, argv)) {
    return Fail(
        kExitBadInput,
        fmt::format(
            "unknown command '{}'; expected run, validate, methods, devices, experiment, ir, "
            "view or psychophysics",
            *word),
        true);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version arrive as "errors" with exit code 0; CLI11 prints them.
    if (e.get_exit_code() == 0) return app.exit(e);
    return Fail(kExitBadInput, e.what(), true);
  }
  return Dispatch(app, o, c);
}

}  // namespace
}  // namespace mrh::cli

int main(int argc, char** argv) {
  using mrh::cli::Fail;
  try {
    return mrh::cli::Main(argc, argv);
  } catch (const mrh::InvalidArgument& e) {
    return Fail(mrh::cli::kExitBadInput, e.what());
  } catch (const mrh::SceneError& e) {
    return Fail(mrh::cli::kExitBadInput, e.what());
  } catch (const std::exception& e) {
    return Fail(mrh::cli::kExitRuntime, e.what());
  } catch (...) {
    return Fail(mrh::cli::kExitRuntime, "unknown internal error; please report it");
  }
}
