// SPDX-License-Identifier: Apache-2.0
// `mrh view` (placeholder until its issue lands: the command exists but reports it is missing).
#include "commands.h"
#include "mrh/core/error.h"

namespace mrh::cli {

CLI::App* AddViewCommand(CLI::App& app, ViewOptions* options) {
  CLI::App* command = app.add_subcommand("view", "(not built yet)");
  command->add_option("session", options->session, "session JSON file")->required();
  return command;
}

int ViewCommand(const ViewOptions&) {
  throw mrh::Error("'mrh view' is not available in this build yet");
}

}  // namespace mrh::cli
