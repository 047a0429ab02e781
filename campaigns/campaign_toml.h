// Typed, checked reads of one TOML table of a campaign file. Every error is a
// fibrenet::InputError of the form "FILE:LINE: KEY: problem; accepted: range", where KEY is the
// dotted path from the file's root (e.g. "budget.max_evaluations", "variables[2].lower").
// Every key read (or declared with Known) is remembered, so that Finish() can reject the keys
// nobody asked for, with a close-match suggestion.
// Internal to campaigns/: only the campaign file reader includes it.
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fibrenet::campaigns {

class CampaignTable {
 public:
  // `path` is the dotted path of `table` ("" for the root); `file` names the file in messages.
  CampaignTable(const toml::table& table, std::string file, std::string path);

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  // The dotted path of `key` inside this table.
  std::string KeyPath(std::string_view key) const;

  bool Has(std::string_view key);
  // Declares keys that are valid here although not read through this reader.
  void Known(std::string_view key);

  // Optional values: std::nullopt when absent; InputError for a wrong type. Number accepts
  // integers and floats; Integer only integers.
  std::optional<double> Number(std::string_view key);
  std::optional<std::int64_t> Integer(std::string_view key);
  std::optional<bool> Bool(std::string_view key);
  std::optional<std::string> String(std::string_view key);
  const toml::table* Table(std::string_view key);
  const toml::array* Array(std::string_view key);

  // Required values: InputError naming the key when absent.
  double RequireNumber(std::string_view key, std::string_view accepted);
  std::string RequireString(std::string_view key, std::string_view accepted);

  // Bounds checks with the standard message.
  double NumberAtLeast(std::string_view key, double fallback, double min, bool inclusive);
  std::int64_t IntegerAtLeast(std::string_view key, std::int64_t fallback, std::int64_t min);
  // A count in [min, max]: a count beyond what a campaign can hold (or an int) is an
  // InputError, not a wrapped value or an allocation failure.
  int Count(std::string_view key, int fallback, int min, int max);

  // Declares the keys accepted here and rejects any other at once, so that a misspelt key is
  // reported as such rather than as a missing required key.
  void Accept(std::initializer_list<std::string_view> keys);

  // Rejects every key of the table that was neither read nor declared Known.
  void Finish() const;

  // Throws InputError for `key` (its line if present, else the table's line).
  [[noreturn]] void Fail(std::string_view key, const std::string& message) const;

 private:
  const toml::node* Get(std::string_view key);
  [[noreturn]] void WrongType(std::string_view key, const char* expected) const;

  const toml::table& table_;
  std::string file_;
  std::string path_;
  std::vector<std::string> known_;
};

// "FILE:LINE: KEY: message" (LINE left out when 0).
std::string Located(const std::string& file, int line, const std::string& key,
                    const std::string& message);

// The source line of a node (0 if unknown).
int LineOf(const toml::node& node);

}  // namespace fibrenet::campaigns
