// SPDX-License-Identifier: Apache-2.0
// `mrh psychophysics` (psychophysics_command.cc): options and dispatch.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <vector>

namespace mrh::cli {

/// `mrh psychophysics run|analyze`.
struct PsychophysicsOptions {
  std::filesystem::path session;              ///< run
  std::string subject;                        ///< run
  std::filesystem::path out;                  ///< run: trials folder; analyze: results
  bool mouse = false;                         ///< run: pointer on the mouse (window)
  bool terminal = false;                      ///< run: no window, answers on stdin
  std::vector<std::string> sets;              ///< run: session overrides
  std::vector<std::filesystem::path> trials;  ///< analyze
};

struct PsychophysicsCommands {
  CLI::App* top = nullptr;
  CLI::App* run = nullptr;
  CLI::App* analyze = nullptr;
};

PsychophysicsCommands AddPsychophysicsCommand(CLI::App& app, PsychophysicsOptions* options);

/// Runs whichever of run/analyze was parsed; returns the exit code.
int PsychophysicsCommand(const PsychophysicsCommands& commands,
                         const PsychophysicsOptions& options);

}  // namespace mrh::cli
