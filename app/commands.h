// Subcommands of the fibrenet CLI, one file each. A command's callback sets the exit code:
// 0 success, 1 run failed, 2 bad input (fibrenet::InputError is turned into 2 by main).
#pragma once

#include <CLI/CLI.hpp>

namespace fibrenet::cli {

struct Context {
  int exit_code = 0;
};

void AddValidateCommand(CLI::App& app, Context& context);
void AddBenchCommand(CLI::App& app, Context& context);
void AddRunCommand(CLI::App& app, Context& context);
void AddCampaignCommand(CLI::App& app, Context& context);
void AddDbCommand(CLI::App& app, Context& context);
void AddReportCommand(CLI::App& app, Context& context);

}  // namespace fibrenet::cli
