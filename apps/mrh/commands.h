// SPDX-License-Identifier: Apache-2.0
// The mrh subcommands: each adds its options to the CLI11 app and runs from the parsed options.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mrh::cli {

/// Exit codes, documented in `mrh --help`.
inline constexpr int kExitOk = 0;
inline constexpr int kExitRuntime = 1;
inline constexpr int kExitBadInput = 2;

/// `mrh run`.
struct RunOptions {
  std::filesystem::path session;
  std::filesystem::path out;       ///< empty: out/<session stem>-<method>
  std::string mode;                ///< empty: the session's
  std::string method;              ///< empty: the session's
  std::optional<double> duration;  ///< s; empty: the session's
  std::vector<std::string> sets;   ///< "dotted.key=value" session overrides
  bool quiet = false;
  bool progress = false;
};

/// `mrh validate`.
struct ValidateOptions {
  std::filesystem::path session;
  std::vector<std::string> sets;
};

/// `mrh experiment`.
struct ExperimentOptions {
  std::string name;
  std::filesystem::path out;  ///< empty: out/<name>
  bool list = false;
  bool quiet = false;
  bool full = false;  ///< the experiment's big sweep
};

/// `mrh ir` (ir_command.cc).
struct IrOptions {
  std::filesystem::path session;
  std::vector<double> pose;  ///< x y z qw qx qy qz (m, unit quaternion), world frame
  std::vector<std::string> sets;
};

/// `mrh view` (view_command.cc).
struct ViewOptions {
  std::filesystem::path session;
  std::vector<std::string> sets;
  int frames = 0;                    ///< > 0: render this many frames headless, then exit
  double at = -1.0;                  ///< >= 0: run headless to this simulated time (s), then exit
  std::filesystem::path screenshot;  ///< with frames or at: write the last frame as PNG here
  std::string method;                ///< empty: the session's
  bool hide_panel = false;           ///< do not draw the ImGui panel
};

CLI::App* AddRunCommand(CLI::App& app, RunOptions* options);
CLI::App* AddIrCommand(CLI::App& app, IrOptions* options);
CLI::App* AddViewCommand(CLI::App& app, ViewOptions* options);
CLI::App* AddValidateCommand(CLI::App& app, ValidateOptions* options);
CLI::App* AddMethodsCommand(CLI::App& app);
CLI::App* AddDevicesCommand(CLI::App& app);
CLI::App* AddExperimentCommand(CLI::App& app, ExperimentOptions* options);

/// Each returns the process exit code. They throw mrh::Error subclasses on bad input or failure;
/// main maps those to exit codes.
int RunCommand(const RunOptions& options);
int ValidateCommand(const ValidateOptions& options);

/// Checks the session's `psychophysics` object, if it has one (file or `sets`), as `mrh
/// psychophysics run` reads it. @throws mrh::InvalidArgument naming the file and key.
void CheckStudy(const std::filesystem::path& session, const std::vector<std::string>& sets);
int MethodsCommand();
int DevicesCommand();
int ExperimentCommand(const ExperimentOptions& options);
int IrCommand(const IrOptions& options);
int ViewCommand(const ViewOptions& options);

/// The `--set KEY=VALUE` option (repeatable, one value per flag), shared by run and validate.
void AddSetOption(CLI::App& command, std::vector<std::string>* sets);

}  // namespace mrh::cli
