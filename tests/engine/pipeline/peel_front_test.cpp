// The peel front ahead of the blade on a row of glue sites 10 um apart (at 5, 15, 25 ... um):
// where the web is glued up to the tip, where a stretch ahead is off, where half a bin still
// holds, and where nothing ahead holds.
#include <gtest/gtest.h>

#include "engine/pipeline/peel_front.h"

namespace fibrenet::pipeline {
namespace {

constexpr double kSpacing = 10e-6, kBin = 50e-6, kTip = 600e-6;
constexpr std::size_t kSites = 100;  // the strip from 0 to 1 mm

PeelFront Row() {
  std::vector<GlueSite> sites;
  // Out of order on purpose: the front sorts its sites.
  for (std::size_t k = kSites; k-- > 0;) sites.push_back({(k + 0.5) * kSpacing, k});
  return PeelFront(sites, kBin, 0.0);
}

// Breaks the sites whose place lies in (from, to).
void BreakBetween(std::vector<std::uint8_t>& broken, double from, double to) {
  for (std::size_t k = 0; k < kSites; ++k) {
    const double x = (k + 0.5) * kSpacing;
    if (x > from && x < to) broken[k] = 1;
  }
}

TEST(PeelFront, AWebGluedUpToTheTipReadsTheDistanceToTheNearestSite) {
  const std::vector<std::uint8_t> broken(kSites, 0);
  EXPECT_NEAR(Row().DelaminatedLength(kTip, broken), 5e-6, 1e-12);
}

TEST(PeelFront, AStretchOffTheYankeeAheadOfTheTipIsTheDelaminatedLength) {
  std::vector<std::uint8_t> broken(kSites, 0);
  BreakBetween(broken, 300e-6, kTip);
  EXPECT_NEAR(Row().DelaminatedLength(kTip, broken), 305e-6, 1e-12);
  // Sites behind the tip, scraped already, do not count either way.
  BreakBetween(broken, kTip, 1e-3);
  EXPECT_NEAR(Row().DelaminatedLength(kTip, broken), 305e-6, 1e-12);
}

TEST(PeelFront, ABinHoldsWhenHalfItsSitesHold) {
  std::vector<std::uint8_t> broken(kSites, 0);
  // The bin next to the tip (550, 600) um: sites 555 ... 595, three of five broken.
  BreakBetween(broken, 570e-6, kTip);
  EXPECT_NEAR(Row().DelaminatedLength(kTip, broken), 600e-6 - 545e-6, 1e-12);
  // Two of five broken: the bin holds, and the front is its intact site nearest the tip.
  broken.assign(kSites, 0);
  BreakBetween(broken, 580e-6, kTip);
  EXPECT_NEAR(Row().DelaminatedLength(kTip, broken), 600e-6 - 575e-6, 1e-12);
}

TEST(PeelFront, AWebOffTheYankeeReadsTheDistanceToTheStripsFarEnd) {
  std::vector<std::uint8_t> broken(kSites, 1);
  EXPECT_NEAR(Row().DelaminatedLength(kTip, broken), kTip, 1e-12);
  EXPECT_THROW(PeelFront({}, 0.0, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace fibrenet::pipeline
