#include "campaigns/table_reader.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/core/error.h"
#include "optimizer/closest_match.h"

namespace fibrenet::campaigns {

using pipeline::Distribution;
using pipeline::DistributionKind;

namespace {

const char* TypeName(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    default: return "nothing";
  }
}

std::string FormatBound(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:g}", v);
}

}  // namespace

bool Range::Contains(double v) const {
  if (!std::isfinite(v)) return false;
  const bool above = lo_open ? v > lo : v >= lo;
  const bool below = hi_open ? v < hi : v <= hi;
  return above && below;
}

std::string Range::Text() const {
  return fmt::format("{}{}, {}{}", lo_open ? "(" : "[", FormatBound(lo), FormatBound(hi),
                     hi_open ? ")" : "]");
}

TableReader::TableReader(const toml::table* table, std::string prefix, ReadContext& ctx)
    : table_(table), prefix_(std::move(prefix)), ctx_(ctx) {}

std::string TableReader::Path(const std::string& key) const {
  return prefix_.empty() ? key : prefix_ + "." + key;
}

void TableReader::Fail(const std::string& key, const std::string& what) const {
  const std::string path = Path(key);
  const bool overridden = ctx_.overrides.count(path) > 0;
  throw InputError(fmt::format("{}: {}{}: {}", ctx_.file, path, overridden ? " (override)" : "",
                               what));
}

const toml::node* TableReader::Get(const std::string& key) {
  asked_.push_back(key);
  ctx_.known.insert(Path(key));
  return table_ ? table_->get(key) : nullptr;
}

bool TableReader::Has(const std::string& key) const { return table_ && table_->contains(key); }

double TableReader::NumberOf(const toml::node& n, const std::string& key) const {
  if (auto v = n.value_exact<double>()) return *v;
  if (auto i = n.value_exact<std::int64_t>()) return static_cast<double>(*i);
  Fail(key, fmt::format("expected a number, got {}", TypeName(n)));
}

void TableReader::CheckRange(const std::string& key, double v, const Range& range,
                             const char* unit) const {
  if (!range.Contains(v))
    Fail(key, fmt::format("{:g} is out of range; accepted {} {}", v, range.Text(), unit));
}

double TableReader::Number(const std::string& key, double fallback, const Range& range,
                           const char* unit) {
  const toml::node* n = Get(key);
  if (!n) return fallback;
  const double v = NumberOf(*n, key);
  CheckRange(key, v, range, unit);
  return v;
}

double TableReader::RequiredNumber(const std::string& key, const Range& range, const char* unit) {
  const toml::node* n = Get(key);
  if (!n) Fail(key, fmt::format("missing; give a number in {} {}", range.Text(), unit));
  const double v = NumberOf(*n, key);
  CheckRange(key, v, range, unit);
  return v;
}

std::int64_t TableReader::Integer(const std::string& key, std::int64_t fallback, std::int64_t lo,
                                  std::int64_t hi) {
  const toml::node* n = Get(key);
  if (!n) return fallback;
  std::int64_t v = 0;
  if (auto i = n->value_exact<std::int64_t>()) {
    v = *i;
  } else if (auto d = n->value_exact<double>(); d && std::nearbyint(*d) == *d && std::abs(*d) < 9e15) {
    v = static_cast<std::int64_t>(*d);
  } else {
    Fail(key, fmt::format("expected an integer in [{}, {}], got {}", lo, hi, TypeName(*n)));
  }
  if (v < lo || v > hi)
    Fail(key, fmt::format("{} is out of range; accepted integers in [{}, {}]", v, lo, hi));
  return v;
}

bool TableReader::Bool(const std::string& key, bool fallback) {
  const toml::node* n = Get(key);
  if (!n) return fallback;
  if (auto b = n->value_exact<bool>()) return *b;
  Fail(key, fmt::format("expected true or false, got {}", TypeName(*n)));
}

std::string TableReader::Choice(const std::string& key, const std::string& fallback,
                                const std::vector<std::string>& choices) {
  const toml::node* n = Get(key);
  if (!n) return fallback;
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "\"" : ", \"") + c + "\"";
  const auto s = n->value_exact<std::string>();
  if (!s) Fail(key, fmt::format("expected one of {}, got {}", list, TypeName(*n)));
  if (std::find(choices.begin(), choices.end(), *s) == choices.end()) {
    const std::string near = optimizer::ClosestMatch(*s, choices);
    Fail(key, fmt::format("\"{}\" is not accepted; accepted: {}{}", *s, list,
                          near.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", near)));
  }
  return *s;
}

const toml::table* TableReader::Table(const std::string& key) {
  const toml::node* n = Get(key);
  if (!n) return nullptr;
  if (const toml::table* t = n->as_table()) return t;
  Fail(key, fmt::format("expected a table, got {}", TypeName(*n)));
}

Distribution TableReader::Dist(const std::string& key, double fallback, const Range& range,
                               const char* unit) {
  const toml::node* n = Get(key);
  if (!n) return Distribution::Fixed(fallback);
  if (!n->is_table()) {
    if (!n->is_number())
      Fail(key, fmt::format("expected a number or a distribution table, got {}", TypeName(*n)));
    const double v = NumberOf(*n, key);
    CheckRange(key, v, range, unit);
    return Distribution::Fixed(v);
  }
  TableReader sub(n->as_table(), Path(key), ctx_);
  const std::string kind = sub.Choice("distribution", "fixed",
                                      {"fixed", "normal", "lognormal", "uniform", "table"});
  Distribution d;
  const double inf = std::numeric_limits<double>::infinity();
  if (kind == "fixed") {
    d = Distribution::Fixed(sub.RequiredNumber("value", range, unit));
  } else if (kind == "uniform") {
    d = Distribution::Uniform(sub.RequiredNumber("min", range, unit),
                              sub.RequiredNumber("max", range, unit));
    if (d.min > d.max) sub.Fail("max", fmt::format("must be >= min = {:g}", d.min));
  } else if (kind == "normal" || kind == "lognormal") {
    d.kind = kind == "normal" ? DistributionKind::kNormal : DistributionKind::kLognormal;
    d.mean = sub.RequiredNumber("mean", range, unit);
    d.sd = sub.RequiredNumber("sd", ClosedOpen(0.0, inf), unit);
    d.min = sub.Number("min", range.lo, range, unit);
    d.max = sub.Number("max", range.hi, range, unit);
    if (d.min > d.max) sub.Fail("max", fmt::format("must be >= min = {:g}", d.min));
    if (d.kind == DistributionKind::kLognormal && !(d.mean > 0.0))
      sub.Fail("mean", "a lognormal law needs mean > 0");
  } else {
    d.kind = DistributionKind::kTable;
    const toml::node* values = sub.Get("values");
    const toml::array* arr = values ? values->as_array() : nullptr;
    if (!arr || arr->empty()) sub.Fail("values", "expected a non-empty array of numbers");
    for (const toml::node& v : *arr) {
      const double x = sub.NumberOf(v, "values");
      sub.CheckRange("values", x, range, unit);
      d.values.push_back(x);
    }
    if (const toml::node* w = sub.Get("weights")) {
      const toml::array* wa = w->as_array();
      if (!wa || wa->size() != d.values.size())
        sub.Fail("weights", fmt::format("expected an array of {} numbers (one per value)",
                                        d.values.size()));
      for (const toml::node& v : *wa) {
        const double x = sub.NumberOf(v, "weights");
        sub.CheckRange("weights", x, ClosedOpen(0.0, inf), "");
        d.weights.push_back(x);
      }
    }
  }
  sub.Finish();
  if (std::string why = d.Validate(); !why.empty()) Fail(key, why);
  return d;
}

void TableReader::Finish() {
  if (!table_) return;
  for (const auto& [k, v] : *table_) {
    const std::string key(k.str());
    if (std::find(asked_.begin(), asked_.end(), key) != asked_.end()) continue;
    const std::string near = optimizer::ClosestMatch(key, asked_);
    const std::string path = Path(key);
    std::vector<std::string> accepted = asked_;
    std::sort(accepted.begin(), accepted.end());
    accepted.erase(std::unique(accepted.begin(), accepted.end()), accepted.end());
    throw InputError(fmt::format("{}: unknown key '{}'{}{}; accepted {}: {}", ctx_.file, path,
                                 ctx_.overrides.count(path) ? " (override)" : "",
                                 near.empty() ? std::string("")
                                              : fmt::format("; did you mean '{}'?", Path(near)),
                                 prefix_.empty() ? "at the top" : "in [" + prefix_ + "]",
                                 fmt::join(accepted, ", ")));
  }
}

}  // namespace fibrenet::campaigns
