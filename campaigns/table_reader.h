// Typed, range-checked reading of one TOML table of a scene file. Every key a reader asks
// for is recorded as known; Finish() then rejects any other key in the table with a
// close-match suggestion. Errors are fibrenet::InputError naming the file, the dotted key
// and the accepted range.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "engine/pipeline/distribution.h"

namespace fibrenet::campaigns {

// What all readers of one file share.
struct ReadContext {
  std::string file;
  std::set<std::string> known;      // every dotted key asked for
  std::set<std::string> overrides;  // dotted keys set by overrides (for messages)
};

// An accepted interval; open ends exclude the bound.
struct Range {
  double lo, hi;
  bool lo_open = false, hi_open = false;
  bool Contains(double v) const;
  std::string Text() const;  // "(0, 100]"
};
inline Range Closed(double lo, double hi) { return {lo, hi, false, false}; }
inline Range OpenClosed(double lo, double hi) { return {lo, hi, true, false}; }
inline Range Open(double lo, double hi) { return {lo, hi, true, true}; }
inline Range ClosedOpen(double lo, double hi) { return {lo, hi, false, true}; }

class TableReader {
 public:
  // table may be null (an absent table: every key takes its default). prefix: dotted path
  // of the table ("" for the root).
  TableReader(const toml::table* table, std::string prefix, ReadContext& ctx);

  // A number in `unit` (for messages), checked against `range`.
  double Number(const std::string& key, double fallback, const Range& range, const char* unit);
  // A required number (no default).
  double RequiredNumber(const std::string& key, const Range& range, const char* unit);
  std::int64_t Integer(const std::string& key, std::int64_t fallback, std::int64_t lo,
                       std::int64_t hi);
  bool Bool(const std::string& key, bool fallback);
  // One of `choices`.
  std::string Choice(const std::string& key, const std::string& fallback,
                     const std::vector<std::string>& choices);
  // A fixed number or a distribution table, in `unit`; every value it can take must lie in
  // `range`. Normal and lognormal laws without min/max are truncated to the range.
  pipeline::Distribution Dist(const std::string& key, double fallback, const Range& range,
                              const char* unit);
  bool Has(const std::string& key) const;
  // A sub-table (null when absent); an error when the key holds something else.
  const toml::table* Table(const std::string& key);

  // Rejects keys nobody asked for. Call after reading every key.
  void Finish();

  std::string Path(const std::string& key) const;
  [[noreturn]] void Fail(const std::string& key, const std::string& what) const;

 private:
  const toml::node* Get(const std::string& key);
  double NumberOf(const toml::node& n, const std::string& path) const;
  void CheckRange(const std::string& path, double v, const Range& range, const char* unit) const;

  const toml::table* table_;
  std::string prefix_;
  ReadContext& ctx_;
  std::vector<std::string> asked_;
};

}  // namespace fibrenet::campaigns
