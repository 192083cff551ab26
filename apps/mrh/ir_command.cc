// SPDX-License-Identifier: Apache-2.0
// `mrh ir` (placeholder until its issue lands: the command exists but reports it is missing).
#include "commands.h"
#include "mrh/core/error.h"

namespace mrh::cli {

CLI::App* AddIrCommand(CLI::App& app, IrOptions* options) {
  CLI::App* command = app.add_subcommand("ir", "(not built yet)");
  command->add_option("session", options->session, "session JSON file")->required();
  return command;
}

int IrCommand(const IrOptions&) {
  throw mrh::Error("'mrh ir' is not available in this build yet");
}

}  // namespace mrh::cli
