// orbit: one binary, one subcommand per job. `orbit --help` lists them.
#include <CLI/CLI.hpp>

#include "cli/command_line.h"
#include "cli/commands.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Orbit: lightweight 3D object recognition from a moving camera.\n"
      "Each subcommand has its own help: orbit SUBCOMMAND --help"};
  int exit_code = 0;
  orbit::cli::AddDescriptorCommand(app, exit_code);
  orbit::cli::AddEnrollCommand(app, exit_code);
  orbit::cli::AddRecognizeCommand(app, exit_code);
  orbit::cli::AddInfoCommand(app, exit_code);
  orbit::cli::AddDemoCommand(app, exit_code);
  orbit::cli::AddImportCommand(app, exit_code);
  orbit::cli::AddListCommand(app, exit_code);
  orbit::cli::AddDeleteCommand(app, exit_code);
  orbit::cli::AddBackupCommand(app, exit_code);
  orbit::cli::AddRestoreCommand(app, exit_code);
  orbit::cli::AddEvalCommand(app, exit_code);
  orbit::cli::AddServeCommand(app, exit_code);
  orbit::cli::AddTokenCommand(app, exit_code);
  orbit::cli::AddLoadtestCommand(app, exit_code);
  orbit::cli::AddWalkCommand(app, exit_code);
  return orbit::cli::RunCommandLine(app, "orbit", argc, argv, exit_code);
}
