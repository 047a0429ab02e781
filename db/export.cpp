#include "db/export.h"

#include <charconv>
#include <optional>
#include <set>
#include <string_view>
#include <vector>

#include "db/queries.h"

namespace fibrenet::db {
namespace {

template <class T>
nlohmann::json or_null(const std::optional<T>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

// Shortest text that parses back to the same double.
std::string number(double v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof(buf), v);
  return ec == std::errc() ? std::string(buf, end) : std::string();
}

std::string number(const std::optional<double>& v) { return v ? number(*v) : std::string(); }

// RFC 4180: quote a field holding a comma, quote or line break, doubling inner quotes.
std::string csv_field(std::string_view s) {
  if (s.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(s);
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  q += '"';
  return q;
}

void write_row(std::ostream& out, const std::vector<std::string>& fields) {
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) out << ',';
    out << csv_field(fields[i]);
  }
  out << '\n';
}

}  // namespace

void to_json(nlohmann::json& j, const MetricValue& m) {
  j = {{"value", m.value},
       {"unit", m.unit},
       {"std_error", or_null(m.std_error)},
       {"n_replicates", m.n_replicates}};
}

void to_json(nlohmann::json& j, const Artifact& a) { j = {{"kind", a.kind}, {"path", a.path}}; }

void to_json(nlohmann::json& j, const CampaignRow& c) {
  j = {{"id", c.id},
       {"name", c.name},
       {"status", c.status},
       {"spec_hash", c.spec_hash},
       {"spec_text", c.spec_text},
       {"software_version", c.software_version},
       {"git_commit", c.git_commit},
       {"created_at", c.created_at},
       {"updated_at", c.updated_at},
       {"counts",
        {{"pending", c.counts.pending},
         {"running", c.counts.running},
         {"done", c.counts.done},
         {"failed", c.counts.failed},
         {"total", c.counts.total()}}}};
}

void to_json(nlohmann::json& j, const CandidateRow& c) {
  nlohmann::json metrics = nlohmann::json::object();
  for (const MetricValue& m : c.metrics) metrics[m.name] = m;
  const auto text_or_null = [](const std::string& s) {
    return s.empty() ? nlohmann::json(nullptr) : nlohmann::json(s);
  };
  j = {{"id", c.id},
       {"campaign", c.campaign},
       {"eval_index", c.eval_index},
       {"key", c.key},
       {"fidelity", c.fidelity},
       {"seeds", c.seeds},
       {"status", std::string(to_string(c.status))},
       {"reason", text_or_null(c.reason)},
       {"created_at", text_or_null(c.created_at)},
       {"started_at", text_or_null(c.started_at)},
       {"ended_at", text_or_null(c.ended_at)},
       {"wall_s", or_null(c.wall_s)},
       {"objective", or_null(c.objective)},
       {"feasible", or_null(c.feasible)},
       {"parameters", c.parameters},
       {"metrics", metrics},
       {"artifacts", c.artifacts},
       {"provenance", c.provenance}};
}

nlohmann::json export_json(const ResultsDb& db, const std::string& campaign) {
  const std::optional<CampaignRow> row = find_campaign(db, campaign);
  if (!row) {
    throw DbError("results database '" + db.path() + "': no campaign named '" + campaign + "'");
  }
  return {{"schema_version", db.schema_version()},
          {"campaign", *row},
          {"candidates", candidates(db, campaign)}};
}

void export_csv(const ResultsDb& db, const std::string& campaign, std::ostream& out) {
  const std::vector<CandidateRow> rows = candidates(db, campaign);
  std::set<std::string> parameter_names;
  std::set<std::string> metric_names;
  for (const CandidateRow& r : rows) {
    for (const auto& [name, value] : r.parameters) parameter_names.insert(name);
    for (const MetricValue& m : r.metrics) metric_names.insert(m.name);
  }

  std::vector<std::string> header = {"candidate_id", "eval_index", "status", "fidelity",
                                     "objective",    "feasible",   "wall_s", "reason"};
  for (const std::string& name : parameter_names) header.push_back("param." + name);
  for (const std::string& name : metric_names) header.push_back("metric." + name);
  write_row(out, header);

  for (const CandidateRow& r : rows) {
    std::vector<std::string> fields = {std::to_string(r.id),
                                       std::to_string(r.eval_index),
                                       std::string(to_string(r.status)),
                                       r.fidelity,
                                       number(r.objective),
                                       r.feasible ? (*r.feasible ? "1" : "0") : "",
                                       number(r.wall_s),
                                       r.reason};
    for (const std::string& name : parameter_names) {
      auto it = r.parameters.find(name);
      fields.push_back(it == r.parameters.end() ? std::string() : number(it->second));
    }
    for (const std::string& name : metric_names) {
      const MetricValue* m = r.metric(name);
      fields.push_back(m ? number(m->value) : std::string());
    }
    write_row(out, fields);
  }
}

}  // namespace fibrenet::db
