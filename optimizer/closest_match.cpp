#include "optimizer/closest_match.h"

#include <algorithm>
#include <cctype>

namespace fibrenet::optimizer {
namespace {

// Levenshtein distance with unit costs, ignoring case; O(|a| |b|) time, O(|b|) memory.
std::size_t EditDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      const std::size_t next = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = row[j];
      row[j] = next;
    }
  }
  return row[b.size()];
}

// True if `name` is an abbreviation of `candidate`: same first letter, and its letters appear
// in `candidate` in order ("max_evals" of "max_evaluations").
bool Abbreviates(std::string_view name, std::string_view candidate) {
  if (name.size() < 3 || candidate.empty() ||
      std::tolower(static_cast<unsigned char>(name[0])) !=
          std::tolower(static_cast<unsigned char>(candidate[0]))) {
    return false;
  }
  std::size_t k = 0;
  for (const char c : candidate) {
    if (k < name.size() && std::tolower(static_cast<unsigned char>(c)) ==
                               std::tolower(static_cast<unsigned char>(name[k]))) {
      ++k;
    }
  }
  return k == name.size();
}

}  // namespace

std::string ClosestMatch(std::string_view name, const std::vector<std::string>& known) {
  std::string best;
  std::size_t best_score = static_cast<std::size_t>(-1);
  for (const std::string& candidate : known) {
    const std::size_t d = EditDistance(name, candidate);
    const std::size_t limit = std::max<std::size_t>(2, std::max(name.size(), candidate.size()) / 2);
    // Abbreviations and extensions ("max_wall" of "max_wall_s") rank as one edit away.
    const bool shortened = Abbreviates(name, candidate) || Abbreviates(candidate, name);
    if (!shortened && d > limit) continue;
    const std::size_t score = shortened ? std::min<std::size_t>(d, 1) : d;
    if (score < best_score) {
      best_score = score;
      best = candidate;
    }
  }
  return best;
}

std::string DidYouMean(std::string_view name, const std::vector<std::string>& known) {
  const std::string match = ClosestMatch(name, known);
  return match.empty() ? std::string() : "; did you mean '" + match + "'?";
}

}  // namespace fibrenet::optimizer
