// orbit: one binary, one subcommand per job. `orbit --help` lists them.
#include <exception>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "cli/rpc_error_text.h"
#include "client/rpc_error.h"
#include "orbit/version.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Orbit: lightweight 3D object recognition from a moving camera.\n"
      "Each subcommand has its own help: orbit SUBCOMMAND --help"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("orbit ") + orbit::kOrbitVersion);

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

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; a usage error (unknown flag, bad value, missing or
    // conflicting options) is printed and exits 2, as for most command-line tools, so that a
    // script can tell it from a command that ran and failed (1).
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const orbit::RpcError& e) {
    // A call to the server failed: say which subcommand, and where it looked for the server.
    const CLI::App* command = app.get_subcommands().front();
    const CLI::Option* server = command->get_option_no_throw("--server");
    std::cerr << orbit::cli::RpcErrorText(
                     command->get_name(),
                     server != nullptr && server->count() > 0 ? server->as<std::string>() : "", e)
              << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "orbit: " << e.what() << "\n";
    return 1;
  }
  return exit_code;
}
