// The subcommands of the `orbit` command-line tool. Each Add*Command registers one subcommand on
// the application; when it runs, its callback stores the process exit code in `exit_code`.
#pragma once

#include <CLI/CLI.hpp>

namespace orbit::cli {

void AddDescriptorCommand(CLI::App& app, int& exit_code);
void AddEnrollCommand(CLI::App& app, int& exit_code);
void AddRecognizeCommand(CLI::App& app, int& exit_code);
void AddInfoCommand(CLI::App& app, int& exit_code);
void AddDemoCommand(CLI::App& app, int& exit_code);
void AddImportCommand(CLI::App& app, int& exit_code);
void AddListCommand(CLI::App& app, int& exit_code);
void AddDeleteCommand(CLI::App& app, int& exit_code);
void AddBackupCommand(CLI::App& app, int& exit_code);
void AddRestoreCommand(CLI::App& app, int& exit_code);
void AddEvalCommand(CLI::App& app, int& exit_code);
void AddServeCommand(CLI::App& app, int& exit_code);
void AddTokenCommand(CLI::App& app, int& exit_code);
void AddLoadtestCommand(CLI::App& app, int& exit_code);
void AddWalkCommand(CLI::App& app, int& exit_code);

}  // namespace orbit::cli
