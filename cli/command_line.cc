#include "cli/command_line.h"

#include <exception>
#include <iostream>
#include <string>

#include "cli/rpc_error_text.h"
#include "client/rpc_error.h"
#include "orbit/version.h"

namespace orbit::cli {

int RunCommandLine(CLI::App& app, const std::string& program, int argc, char** argv,
                   const int& exit_code) {
  app.require_subcommand(1);
  app.set_version_flag("--version", program + " " + kOrbitVersion);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const RpcError& e) {
    const CLI::App* command = app.get_subcommands().front();
    const CLI::Option* server = command->get_option_no_throw("--server");
    std::cerr << RpcErrorText(
                     command->get_name(),
                     server != nullptr && server->count() > 0 ? server->as<std::string>() : "", e)
              << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return 1;
  }
  return exit_code;
}

}  // namespace orbit::cli
