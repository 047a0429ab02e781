#include "campaigns/campaign_toml.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "engine/core/error.h"
#include "optimizer/closest_match.h"

namespace fibrenet::campaigns {

std::string Located(const std::string& file, int line, const std::string& key,
                    const std::string& message) {
  const std::string where = line > 0 ? fmt::format("{}:{}", file, line) : file;
  return key.empty() ? fmt::format("{}: {}", where, message)
                     : fmt::format("{}: {}: {}", where, key, message);
}

int LineOf(const toml::node& node) { return static_cast<int>(node.source().begin.line); }

CampaignTable::CampaignTable(const toml::table& table, std::string file, std::string path)
    : table_(table), file_(std::move(file)), path_(std::move(path)) {}

std::string CampaignTable::KeyPath(std::string_view key) const {
  if (key.empty()) return path_;
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void CampaignTable::Known(std::string_view key) {
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
}

const toml::node* CampaignTable::Get(std::string_view key) {
  Known(key);
  return table_.get(key);
}

bool CampaignTable::Has(std::string_view key) { return Get(key) != nullptr; }

void CampaignTable::Fail(std::string_view key, const std::string& message) const {
  const toml::node* node = table_.get(key);
  const int line = node ? LineOf(*node) : LineOf(table_);
  throw InputError(Located(file_, line, KeyPath(key), message));
}

void CampaignTable::WrongType(std::string_view key, const char* expected) const {
  const toml::node* node = table_.get(key);
  std::ostringstream type;
  if (node) type << node->type();
  Fail(key, fmt::format("must be {}; got a {}", expected, node ? type.str() : "nothing"));
}

std::optional<double> CampaignTable::Number(std::string_view key) {
  const toml::node* node = Get(key);
  if (!node) return std::nullopt;
  if (const auto* i = node->as_integer()) return static_cast<double>(i->get());
  if (const auto* f = node->as_floating_point()) return f->get();
  WrongType(key, "a number");
}

std::optional<std::int64_t> CampaignTable::Integer(std::string_view key) {
  const toml::node* node = Get(key);
  if (!node) return std::nullopt;
  if (const auto* i = node->as_integer()) return i->get();
  WrongType(key, "an integer");
}

std::optional<bool> CampaignTable::Bool(std::string_view key) {
  const toml::node* node = Get(key);
  if (!node) return std::nullopt;
  if (const auto* b = node->as_boolean()) return b->get();
  WrongType(key, "true or false");
}

std::optional<std::string> CampaignTable::String(std::string_view key) {
  const toml::node* node = Get(key);
  if (!node) return std::nullopt;
  if (const auto* s = node->as_string()) return s->get();
  WrongType(key, "a string");
}

const toml::table* CampaignTable::Table(std::string_view key) {
  const toml::node* node = Get(key);
  if (!node) return nullptr;
  if (const auto* t = node->as_table()) return t;
  WrongType(key, "a table");
}

const toml::array* CampaignTable::Array(std::string_view key) {
  const toml::node* node = Get(key);
  if (!node) return nullptr;
  if (const auto* a = node->as_array()) return a;
  WrongType(key, "an array");
}

double CampaignTable::RequireNumber(std::string_view key, std::string_view accepted) {
  if (auto v = Number(key)) return *v;
  Fail(key, fmt::format("is required; accepted: {}", accepted));
}

std::string CampaignTable::RequireString(std::string_view key, std::string_view accepted) {
  if (auto v = String(key)) return *v;
  Fail(key, fmt::format("is required; accepted: {}", accepted));
}

double CampaignTable::NumberAtLeast(std::string_view key, double fallback, double min,
                                    bool inclusive) {
  const double v = Number(key).value_or(fallback);
  if (!(std::isfinite(v) && (inclusive ? v >= min : v > min))) {
    Fail(key, fmt::format("must be a finite number {} {}; got {}", inclusive ? ">=" : ">", min, v));
  }
  return v;
}

std::int64_t CampaignTable::IntegerAtLeast(std::string_view key, std::int64_t fallback,
                                           std::int64_t min) {
  const std::int64_t v = Integer(key).value_or(fallback);
  if (v < min) Fail(key, fmt::format("must be an integer >= {}; got {}", min, v));
  return v;
}

int CampaignTable::Count(std::string_view key, int fallback, int min, int max) {
  const std::int64_t v = IntegerAtLeast(key, fallback, min);
  if (v > max) Fail(key, fmt::format("must be an integer <= {}; got {}", max, v));
  return static_cast<int>(v);
}

void CampaignTable::Accept(std::initializer_list<std::string_view> keys) {
  for (std::string_view key : keys) Known(key);
  Finish();
}

void CampaignTable::Finish() const {
  for (const auto& [key, node] : table_) {
    const std::string_view name = key.str();
    if (std::find(known_.begin(), known_.end(), name) != known_.end()) continue;
    std::vector<std::string> sorted = known_;
    std::sort(sorted.begin(), sorted.end());
    throw InputError(
        Located(file_, LineOf(node), KeyPath(name),
                fmt::format("unknown key{}; accepted here: {}", optimizer::DidYouMean(name, sorted),
                            fmt::join(sorted, ", "))));
  }
}

}  // namespace fibrenet::campaigns
