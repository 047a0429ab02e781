// `fibrenet report --db FILE --out DIR [--campaign NAME]`: PNG plots of campaigns, drawn by
// scripts/report.py (Python + matplotlib) from the SQLite file: objective against evaluation,
// the softness-strength scatter with the feasible region and the Pareto front, and each design
// variable against each goal metric (docs/campaigns.md).
#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.h"
#include "engine/core/error.h"

extern char** environ;

namespace fibrenet::cli {

namespace {

namespace fs = std::filesystem;

struct ReportOptions {
  std::string db_path;
  std::string out_dir;
  std::string campaign;
  bool json = false;
};

// scripts/report.py: $FIBRENET_SCRIPTS_DIR, else next to the build folder of this binary
// (build/fibrenet -> scripts/), else the source tree this binary was built from.
fs::path FindScript() {
  std::vector<fs::path> candidates;
  if (const char* dir = std::getenv("FIBRENET_SCRIPTS_DIR")) candidates.emplace_back(dir);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(exe.parent_path().parent_path() / "scripts");
  candidates.emplace_back(FIBRENET_SCRIPTS_DIR);
  for (const fs::path& dir : candidates) {
    if (fs::is_regular_file(dir / "report.py")) return dir / "report.py";
  }
  throw RunError("cannot find scripts/report.py (set FIBRENET_SCRIPTS_DIR to its folder)");
}

// Runs `args` (args[0] looked up in PATH) and returns its exit code, or -1 if it could not be
// started or was killed. With `quiet` its output goes to /dev/null.
int RunProcess(std::vector<std::string> args, bool quiet) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (quiet) {
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  }
  std::cout << std::flush;
  std::cerr << std::flush;
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

// The first Python with matplotlib among $FIBRENET_PYTHON, python3 on the PATH and the
// system's /usr/bin/python3 (a virtual environment on the PATH may lack matplotlib).
std::string FindPython() {
  std::vector<std::string> candidates;
  if (const char* python = std::getenv("FIBRENET_PYTHON")) candidates.emplace_back(python);
  candidates.emplace_back("python3");
  candidates.emplace_back("/usr/bin/python3");
  for (const std::string& python : candidates) {
    if (RunProcess({python, "-c", "import matplotlib"}, true) == 0) return python;
  }
  throw RunError(
      "the report needs Python 3 with matplotlib (apt-get install python3-matplotlib, "
      "or set FIBRENET_PYTHON to a python that has it)");
}

int RunReport(const ReportOptions& o) {
  std::error_code ec;
  if (!fs::is_regular_file(o.db_path, ec)) {
    throw InputError(fmt::format("--db {}: no such file", o.db_path));
  }
  const fs::path script = FindScript();
  std::vector<std::string> args = {FindPython(), script.string(), "--db",
                                   o.db_path,    "--out",         o.out_dir};
  if (!o.campaign.empty()) {
    args.push_back("--campaign");
    args.push_back(o.campaign);
  }
  if (o.json) args.push_back("--json");
  const int code = RunProcess(args, false);
  if (code == 2) throw InputError("report: bad input (see the message above)");
  if (code != 0) {
    throw RunError(fmt::format("report: {} failed (exit code {})", script.string(), code));
  }
  return 0;
}

}  // namespace

void AddReportCommand(CLI::App& app, Context& context) {
  auto o = std::make_shared<ReportOptions>();
  CLI::App* cmd = app.add_subcommand("report", "Plots of campaigns (PNG) from a results database");
  cmd->add_option("--db", o->db_path, "Results database (SQLite)")->required();
  cmd->add_option("--out", o->out_dir, "Folder for the PNG files (created)")->required();
  cmd->add_option("--campaign", o->campaign, "Only this campaign (default: every campaign)");
  cmd->add_flag("--json", o->json, "Print the list of written files as JSON on stdout");
  cmd->callback([o, &context] { context.exit_code = RunReport(*o); });
}

}  // namespace fibrenet::cli
