#include "engine/pipeline/peel_front.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace fibrenet::pipeline {

PeelFront::PeelFront(std::vector<GlueSite> sites, double bin, double far_end)
    : sites_(std::move(sites)), bin_(bin), far_end_(far_end) {
  if (!(bin > 0.0)) throw std::invalid_argument("PeelFront: the bin width must be > 0");
  std::sort(sites_.begin(), sites_.end(),
            [](const GlueSite& a, const GlueSite& b) { return a.x < b.x; });
}

double PeelFront::DelaminatedLength(double tip_x, const std::vector<std::uint8_t>& broken) const {
  // Sites [0, ahead) lie ahead of the tip; walk them from the tip forwards, one bin at a time.
  auto ahead = std::lower_bound(sites_.begin(), sites_.end(), tip_x,
                                [](const GlueSite& s, double x) { return s.x < x; });
  for (double bin_end = tip_x - bin_; ahead != sites_.begin(); bin_end -= bin_) {
    std::size_t count = 0, intact = 0;
    double nearest_intact = 0.0;
    auto site = ahead;
    while (site != sites_.begin() && (site - 1)->x > bin_end) {
      --site;
      ++count;
      if (broken[site->bond]) continue;
      if (intact++ == 0) nearest_intact = site->x;
    }
    if (count > 0 && 2 * intact >= count) return tip_x - nearest_intact;
    ahead = site;
  }
  return std::max(0.0, tip_x - far_end_);
}

}  // namespace fibrenet::pipeline
