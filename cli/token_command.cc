// orbit token: makes a new token and the token-file line that grants it (server/token_file.h).
// The token goes to whoever will call (a device, an operator) and is not kept anywhere; the
// line goes into the server's token file, which then holds only the token's SHA-256.
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "server/token_file.h"

namespace orbit::cli {

void AddTokenCommand(CLI::App& app, int& exit_code) {
  struct Options {
    std::string name;
    std::string role = "recognize";
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "token",
      "Make a new token for `orbit serve --tokens FILE`. Prints two lines: the token, to give\n"
      "to the device or operator that will call (clients send it as `authorization: Bearer\n"
      "<token>`; orbit's networked commands take --token or --token-file), and the line to\n"
      "append to FILE, which holds only the token's SHA-256 under NAME. The token itself is\n"
      "not kept: lose it and make another.\n"
      "The server reads FILE again on SIGHUP or when it changes.\n"
      "  orbit token --name phone-7 --role recognize");
  cmd->add_option("--name", o->name,
                  "the token's name in the server's audit log, its limits and its revocation\n"
                  "(1..64 letters, digits, '_', '-' or '.')")
      ->required();
  cmd->add_option("--role", o->role, "recognize (sessions and reads) or admin (also changes)")
      ->check(CLI::IsMember({"recognize", "admin"}))
      ->capture_default_str();
  cmd->callback([o, &exit_code] {
    const server::Role role = o->role == "admin" ? server::Role::kAdmin : server::Role::kRecognize;
    if (!server::IsTokenName(o->name)) {
      throw CLI::ValidationError("--name",
                                 "'" + o->name + "' is not 1..64 letters, digits, '_', '-' or '.'");
    }
    const std::string token = server::NewToken();
    const std::string line = server::TokenFileLine(o->name, role, token);
    std::cout << token << "\n" << line << "\n";
    exit_code = 0;
  });
}

}  // namespace orbit::cli
