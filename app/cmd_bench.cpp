#include "app/commands.h"

namespace fibrenet::cli {
void AddBenchCommand(CLI::App&, Context&) {}
}  // namespace fibrenet::cli
