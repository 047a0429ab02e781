// `fibrenet validate [--json] [--case NAME]`: the physics validation suite.
#include <chrono>
#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "engine/core/error.h"
#include "engine/validation/case.h"

namespace fibrenet::cli {

namespace {

struct ValidateOptions {
  bool json = false;
  std::vector<std::string> cases;
  bool list = false;
};

int RunValidate(const ValidateOptions& o) {
  using validation::Cases;
  std::vector<const validation::CaseEntry*> selected;
  for (const auto& name : o.cases) {
    const validation::CaseEntry* found = nullptr;
    for (const auto& c : Cases())
      if (name == c.name) found = &c;
    if (!found) {
      std::string known;
      for (const auto& c : Cases()) known += std::string(known.empty() ? "" : ", ") + c.name;
      throw InputError(fmt::format("--case '{}': no such validation case; accepted: {}", name, known));
    }
    selected.push_back(found);
  }
  if (selected.empty())
    for (const auto& c : Cases()) selected.push_back(&c);
  if (o.list) {
    for (const auto* c : selected) std::cout << fmt::format("{:24} {}\n", c->name, c->description);
    return 0;
  }

  nlohmann::json cases = nlohmann::json::array();
  bool all_passed = true;
  if (!o.json)
    std::cout << fmt::format("{:24} {:30} {:>10} {:>10} {:>6} {:>8}\n", "case", "fidelity",
                             "error", "tolerance", "pass", "wall_s");
  for (const auto* c : selected) {
    if (o.json) std::cerr << "validate: " << c->name << "\n";
    for (const validation::CaseResult& r : c->run()) {
      all_passed = all_passed && r.passed;
      cases.push_back({{"name", r.name},
                       {"fidelity", r.fidelity},
                       {"default", r.is_default},
                       {"error", r.error},
                       {"tolerance", r.tolerance},
                       {"passed", r.passed},
                       {"wall_s", r.wall_s},
                       {"detail", r.detail}});
      if (!o.json)
        std::cout << fmt::format("{:24} {:30} {:10.3e} {:10.3e} {:>6} {:8.3f}  {}\n", r.name,
                                 r.fidelity, r.error, r.tolerance, r.passed ? "yes" : "NO",
                                 r.wall_s, r.detail)
                  << std::flush;
    }
  }
  if (o.json) std::cout << nlohmann::json{{"cases", cases}, {"passed", all_passed}}.dump(2) << "\n";
  else std::cout << (all_passed ? "all cases passed\n" : "SOME CASES FAILED\n");
  return all_passed ? 0 : 1;
}

}  // namespace

void AddValidateCommand(CLI::App& app, Context& context) {
  auto options = std::make_shared<ValidateOptions>();
  CLI::App* cmd = app.add_subcommand("validate", "Run the physics validation suite");
  cmd->add_flag("--json", options->json, "Print one JSON document on stdout");
  cmd->add_option("--case", options->cases, "Run only this case (repeatable)");
  cmd->add_flag("--list", options->list, "List the cases and exit");
  cmd->callback([options, &context] { context.exit_code = RunValidate(*options); });
}

}  // namespace fibrenet::cli
