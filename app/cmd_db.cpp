// `fibrenet db list|show|best|export --db FILE ...`: reads the results database (read-only,
// so it is safe while a campaign writes the file).
//   db list                                   campaigns with candidate counts
//   db show CANDIDATE_ID                      one candidate: parameters, metrics, artifacts
//   db best --campaign NAME [-n N]            best candidates, ranked against the goals
//   db export --campaign NAME --format csv|json [--out FILE]
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/commands.h"
#include "campaigns/campaign_file.h"
#include "db/error.h"
#include "db/export.h"
#include "db/queries.h"
#include "db/results_db.h"
#include "engine/core/error.h"
#include "optimizer/closest_match.h"

namespace fibrenet::cli {

namespace {

struct DbOptions {
  std::string db_path;
  bool json = false;
  std::int64_t candidate_id = 0;
  std::string campaign;
  int n = 5;
  std::string format = "csv";
  std::string out;
};

// Runs `body` on the database opened read-only; every database error is bad input here (a
// wrong path, not a results database, no such campaign).
template <typename Body>
int WithDb(const DbOptions& o, Body body) {
  try {
    const db::ResultsDb db(o.db_path, db::OpenMode::kReadOnly);
    return body(db);
  } catch (const db::DbError& e) {
    throw InputError(fmt::format("--db {}: {}", o.db_path, e.what()));
  }
}

// The campaign called o.campaign, or InputError listing the campaigns the file holds.
db::CampaignRow RequireCampaign(const db::ResultsDb& db, const DbOptions& o) {
  if (auto campaign = db::find_campaign(db, o.campaign)) return *campaign;
  std::vector<std::string> names;
  for (const db::CampaignRow& c : db::list_campaigns(db)) names.push_back(c.name);
  throw InputError(fmt::format("--campaign '{}': no such campaign in {}{}; accepted: {}",
                               o.campaign, o.db_path, optimizer::DidYouMean(o.campaign, names),
                               names.empty() ? "none (the database holds no campaign)"
                                             : fmt::format("{}", fmt::join(names, ", "))));
}

// CLI11 says only "Could not convert" for a bad integer; this also says what is accepted.
CLI::Validator IntegerOption(std::int64_t min, const std::string& accepted) {
  return CLI::Validator(
      [min, accepted](std::string& text) {
        try {
          std::size_t used = 0;
          const long long v = std::stoll(text, &used);
          if (used == text.size() && v >= min) return std::string();
        } catch (const std::exception&) {
        }
        return fmt::format("'{}' is not accepted; accepted: {}", text, accepted);
      },
      "INTEGER");
}

std::string Optional(const std::optional<double>& v) {
  return v ? fmt::format("{:.6g}", *v) : std::string("-");
}

int List(const DbOptions& o) {
  return WithDb(o, [&](const db::ResultsDb& db) {
    const auto rows = db::list_campaigns(db);
    if (o.json) {
      std::cout << nlohmann::json{{"campaigns", rows}}.dump(2) << "\n";
      return 0;
    }
    std::cout << fmt::format("{:>4}  {:24} {:10} {:>6} {:>6} {:>7} {:>7}  {}\n", "id", "campaign",
                             "status", "done", "failed", "running", "pending", "updated");
    for (const db::CampaignRow& c : rows) {
      std::cout << fmt::format("{:>4}  {:24} {:10} {:>6} {:>6} {:>7} {:>7}  {}\n", c.id, c.name,
                               c.status, c.counts.done, c.counts.failed, c.counts.running,
                               c.counts.pending, c.updated_at);
    }
    return 0;
  });
}

int Show(const DbOptions& o) {
  return WithDb(o, [&](const db::ResultsDb& db) {
    const auto row = db::candidate(db, o.candidate_id);
    if (!row)
      throw InputError(fmt::format("--db {}: no candidate with id {}; accepted: the id of a stored "
                                   "candidate (db best and db export list them)",
                                   o.db_path, o.candidate_id));
    if (o.json) {
      std::cout << nlohmann::json(*row).dump(2) << "\n";
      return 0;
    }
    std::cout << fmt::format("candidate {} of campaign '{}' (#{}), fidelity '{}', status {}\n",
                             row->id, row->campaign, row->eval_index, row->fidelity,
                             db::to_string(row->status));
    if (!row->reason.empty()) std::cout << "reason: " << row->reason << "\n";
    std::cout << fmt::format("objective {}, feasible {}, wall {} s\n", Optional(row->objective),
                             row->feasible ? (*row->feasible ? "yes" : "no") : "-",
                             Optional(row->wall_s));
    std::cout << fmt::format("started {}, ended {}\n", row->started_at, row->ended_at);
    std::cout << "parameters:\n";
    for (const auto& [name, value] : row->parameters) {
      std::cout << fmt::format("  {} = {:.10g}\n", name, value);
    }
    if (!row->metrics.empty()) std::cout << "metrics:\n";
    for (const db::MetricValue& m : row->metrics) {
      std::cout << fmt::format(
          "  {} = {:.10g}{}{}\n", m.name, m.value, m.unit == "1" ? std::string() : " " + m.unit,
          m.std_error ? fmt::format(" (+- {:.3g}, {} replicates)", *m.std_error, m.n_replicates)
                      : "");
    }
    for (const db::Artifact& a : row->artifacts) {
      std::cout << fmt::format("artifact {}: {}\n", a.kind, a.path);
    }
    return 0;
  });
}

// The goals of a stored campaign, or nullopt if its file no longer parses with this build.
std::optional<optimizer::Goals> StoredGoals(const db::CampaignRow& c) {
  try {
    return campaigns::ParseCampaign(c.spec_text, "campaign '" + c.name + "' (stored)", ".",
                                    campaigns::ParseMode::kStored)
        .goals;
  } catch (const InputError&) {
    return std::nullopt;
  }
}

// Each goal metric of `row` with its bound and whether it is met.
nlohmann::json GoalStatus(const optimizer::Goals& goals, const db::CandidateRow& row) {
  nlohmann::json out = nlohmann::json::object();
  for (const optimizer::Constraint& c : goals.constraints()) {
    const db::MetricValue* m = row.metric(c.metric);
    const bool met = m && (!c.min || m->value >= *c.min) && (!c.max || m->value <= *c.max);
    out[c.metric] = {{"value", m ? nlohmann::json(m->value) : nlohmann::json(nullptr)},
                     {"min", c.min ? nlohmann::json(*c.min) : nlohmann::json(nullptr)},
                     {"max", c.max ? nlohmann::json(*c.max) : nlohmann::json(nullptr)},
                     {"met", met}};
  }
  return out;
}

int Best(const DbOptions& o) {
  return WithDb(o, [&](const db::ResultsDb& db) {
    const db::CampaignRow campaign = RequireCampaign(db, o);
    const auto rows = db::best(db, o.campaign, o.n);
    const auto goals = StoredGoals(campaign);
    if (o.json) {
      nlohmann::json list = nlohmann::json::array();
      for (const auto& row : rows) {
        nlohmann::json j = row;
        if (goals) j["goals"] = GoalStatus(*goals, row);
        list.push_back(j);
      }
      std::cout << nlohmann::json{{"campaign", o.campaign}, {"best", list}}.dump(2) << "\n";
      return 0;
    }
    std::cout << fmt::format("best candidates of '{}' (feasible first, then lowest objective)\n",
                             o.campaign);
    int rank = 1;
    for (const auto& row : rows) {
      std::cout << fmt::format("{:>3}. candidate {} (#{}, {}): objective {}, {}\n", rank++, row.id,
                               row.eval_index, row.fidelity, Optional(row.objective),
                               row.feasible && *row.feasible ? "feasible" : "INFEASIBLE");
      for (const auto& [name, value] : row.parameters) {
        std::cout << fmt::format("       {} = {:.6g}\n", name, value);
      }
      if (!goals) continue;
      const nlohmann::json statuses = GoalStatus(*goals, row);
      for (const auto& [metric, status] : statuses.items()) {
        std::string bound;
        if (!status["min"].is_null())
          bound += fmt::format(">= {:.6g} ", status["min"].get<double>());
        if (!status["max"].is_null())
          bound += fmt::format("<= {:.6g} ", status["max"].get<double>());
        std::cout << fmt::format(
            "       {} = {} (goal {}: {})\n", metric,
            status["value"].is_null() ? std::string("missing")
                                      : fmt::format("{:.6g}", status["value"].get<double>()),
            bound.substr(0, bound.size() - 1), status["met"].get<bool>() ? "met" : "NOT met");
      }
    }
    if (rows.empty()) std::cout << "no finished candidates yet\n";
    return 0;
  });
}

int Export(const DbOptions& o) {
  const std::string format = o.json ? "json" : o.format;
  if (format != "csv" && format != "json") {
    throw InputError(fmt::format("--format '{}': accepted: csv, json", format));
  }
  return WithDb(o, [&](const db::ResultsDb& db) {
    RequireCampaign(db, o);
    std::ofstream file;
    if (!o.out.empty()) {
      file.open(o.out, std::ios::binary);
      if (!file) {
        throw InputError(fmt::format("--out {}: cannot write the file; accepted: a file in an "
                                     "existing, writable folder",
                                     o.out));
      }
    }
    std::ostream& out = o.out.empty() ? std::cout : file;
    if (format == "json") {
      out << db::export_json(db, o.campaign).dump(2) << "\n";
    } else {
      db::export_csv(db, o.campaign, out);
    }
    out.flush();
    if (!out) throw RunError("writing the export failed");
    return 0;
  });
}

}  // namespace

void AddDbCommand(CLI::App& app, Context& context) {
  CLI::App* dbc = app.add_subcommand("db", "Query the results database");
  dbc->require_subcommand(1);
  auto o = std::make_shared<DbOptions>();
  auto common = [&](CLI::App* cmd) {
    cmd->add_option("--db", o->db_path, "Results database (SQLite)")->required();
    cmd->add_flag("--json", o->json, "Print one JSON document on stdout");
  };
  CLI::App* list = dbc->add_subcommand("list", "Campaigns with candidate counts");
  common(list);
  list->callback([o, &context] { context.exit_code = List(*o); });

  CLI::App* show = dbc->add_subcommand("show", "One candidate in full");
  show->add_option("candidate", o->candidate_id, "Candidate id")
      ->required()
      ->check(IntegerOption(1, "a candidate id, an integer >= 1"));
  common(show);
  show->callback([o, &context] { context.exit_code = Show(*o); });

  CLI::App* best = dbc->add_subcommand("best", "Best candidates of a campaign against its goals");
  best->add_option("--campaign", o->campaign, "Campaign name")->required();
  best->add_option("-n", o->n, "How many (negative: all)")
      ->capture_default_str()
      ->check(IntegerOption(std::numeric_limits<int>::min(), "an integer (negative: all)"));
  common(best);
  best->callback([o, &context] { context.exit_code = Best(*o); });

  CLI::App* exp = dbc->add_subcommand("export", "Export a campaign as CSV or JSON");
  exp->add_option("--campaign", o->campaign, "Campaign name")->required();
  exp->add_option("--format", o->format, "csv or json")->capture_default_str();
  exp->add_option("--out", o->out, "Write to this file instead of stdout");
  common(exp);
  exp->callback([o, &context] { context.exit_code = Export(*o); });
}

}  // namespace fibrenet::cli
