// orbit-server: the subcommands a server machine runs, each as `orbit` runs it (same flags, same
// ORBIT_* variables, same output), in a binary that holds none of the device side of `orbit`
// (captures, object tracking, evaluation) and so needs none of its libraries: the server image
// ships it (docker/Dockerfile). `info` is the image's health check; `token` and `backup` work on
// the files a server owns.
#include <CLI/CLI.hpp>

#include "cli/command_line.h"
#include "cli/commands.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Orbit's server: `orbit serve` and the commands that look after it, without the device-side "
      "commands of `orbit`.\n"
      "Each subcommand has its own help: orbit-server SUBCOMMAND --help"};
  int exit_code = 0;
  orbit::cli::AddServeCommand(app, exit_code);
  orbit::cli::AddInfoCommand(app, exit_code);
  orbit::cli::AddTokenCommand(app, exit_code);
  orbit::cli::AddBackupCommand(app, exit_code);
  return orbit::cli::RunCommandLine(app, "orbit-server", argc, argv, exit_code);
}
