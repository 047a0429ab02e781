// How far ahead of the doctor blade the sheet has come off the Yankee: the delaminated length.
// Creped tissue folds because the web delaminates over short lengths at the blade; a web whose
// scraped part peels it off far ahead is thrown off whole instead (docs/creping.md).
//
// The glue sites (the sheet's particles held by adhesive bonds, at their places on the Yankee)
// are binned along MD from the tip forwards, the way the blade runs (towards -x). The peel
// front lies in the first bin in which at least half of the sites still hold, at the intact
// site nearest the tip; the delaminated length is its distance from the tip. A web glued up to
// the blade reads about the sites' spacing; a web off the Yankee altogether reads the distance
// from the tip to the strip's far end.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fibrenet::pipeline {

struct GlueSite {
  double x = 0.0;       // place on the Yankee along MD [m]
  std::size_t bond = 0;  // its adhesive bond
};

class PeelFront {
 public:
  // bin: MD width of a bin [m], > 0; far_end: the strip's end the blade reaches last (its
  // lowest x) [m].
  PeelFront(std::vector<GlueSite> sites, double bin, double far_end);
  // broken: the world's bonds' broken flags.
  double DelaminatedLength(double tip_x, const std::vector<std::uint8_t>& broken) const;

 private:
  std::vector<GlueSite> sites_;  // by x
  double bin_ = 0.0, far_end_ = 0.0;
};

}  // namespace fibrenet::pipeline
