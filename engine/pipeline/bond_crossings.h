// Fibre-fibre bonds grouped into crossings. Where two fibres touch, their particles make as
// many bonds as the discretisation puts in contact (about 2.4 a crossing at one diameter's
// spacing, 6.3 at half a diameter), so a model whose bond properties are per particle pair
// changes with the spacing. A crossing is the physical bond (paper 2.3): the particle bonds
// that join the same two fibres at the same place.
//
// Two intact fibre-fibre bonds belong to one crossing when they join the same two fibres and
// their particles lie within `reach` places of each other along both fibres, where reach is
// the particles in one diameter plus one (2 at one diameter's spacing, 3 at half), and so on
// transitively: an oblique or parallel contact is one crossing however long, while a curled
// fibre that meets the same fibre again further along makes a second one.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/pipeline/network.h"

namespace fibrenet::pipeline {

struct BondCrossings {
  std::vector<std::int32_t> bonds;     // the intact fibre-fibre bonds, in id order
  std::vector<std::int32_t> crossing;  // crossing id of each, numbered from 0
  std::vector<std::int32_t> size;      // particle bonds in each crossing
};

// Groups the network's intact fibre-fibre bonds into crossings as described above.
BondCrossings GroupBondsByCrossing(const Network& net);

// Places along its fibre within which two particle bonds join at one crossing: the
// particles in one diameter, rounded up, plus one.
std::int32_t CrossingReach(const FibreRecord& f);

}  // namespace fibrenet::pipeline
