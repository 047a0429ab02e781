// Patterns for patterned walls (engine/core/relief.h): the bosses of an embossing plate and
// the open pockets of a through-air-drying fabric. A pattern is a square lattice of round
// dots or a set of parallel lines along x (machine direction), each with a flat top of
// `size` minus one `flank` and a cosine flank of width `flank` on each side:
//   level(d) = 1 for d <= size/2 - flank/2, 0 for d >= size/2 + flank/2, and
//   (1 + cos(pi (d - size/2 + flank/2) / flank)) / 2 between,
// d the distance from the dot's centre (or the line's axis). The pitch is rounded so that a
// whole number of periods fits the periodic cell.
#pragma once

#include <memory>
#include <string>

#include "engine/core/cell.h"
#include "engine/core/relief.h"
#include "engine/core/world.h"

namespace fibrenet::pipeline {

enum class ReliefShape { kDots, kLines };

struct ReliefPattern {
  ReliefShape shape = ReliefShape::kDots;
  double pitch = 500e-6;   // centre-to-centre spacing [m]
  double size = 250e-6;    // dot diameter or line width at half height [m]
  double height = 100e-6;  // boss height or pocket depth [m]
  double flank = 50e-6;    // width of each smooth flank [m]

  std::string Validate() const;  // empty when valid
};

// The pattern on `cell`, heights times `sign` (+1 bosses towards the particles, -1 pockets),
// sampled every `resolution` metres or finer.
std::shared_ptr<const Relief> MakeRelief(const ReliefPattern& pattern, const Cell& cell,
                                         double sign, double resolution = 5e-6);

// Level in [0, 1] of the pattern at (x, y) on `relief` (|height| / max |height|).
double ReliefLevel(const Relief& relief, double x, double y);

// How deep the pattern is imprinted in the sheet: mean particle height over the flat part of
// the pattern (level < 0.1) minus that over the patterned part (level > 0.5) [m]; positive
// when the bosses pressed the sheet down, or the pockets drew it in.
double Imprint(const World& w, const Relief& relief);

}  // namespace fibrenet::pipeline
