// What every Orbit command-line binary does around its subcommands: `orbit`, and `orbit-server`,
// the subset a server machine runs (cli/server_main.cc). One subcommand is required, --version
// prints the version, and a failure becomes an exit status and a message on stderr.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace orbit::cli {

// Requires one of the subcommands registered on `app`, adds --version (prints "`program`
// VERSION"), parses `argv`, runs the chosen subcommand and returns the process's exit status:
// `exit_code` as the subcommand left it when it ran; 0 after --help or --version; 2 for a usage
// error (unknown flag, bad value, missing or conflicting options), so that a script can tell it
// from a command that ran and failed; 1 when the subcommand threw, with its message on stderr
// (prefixed "`program`: "; a failed call to a server names the subcommand and the --server it
// was given).
int RunCommandLine(CLI::App& app, const std::string& program, int argc, char** argv,
                   const int& exit_code);

}  // namespace orbit::cli
