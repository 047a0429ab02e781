#include "optimizer/design_space.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.h"

namespace fibrenet::optimizer {
namespace {

Variable Linear(const std::string& key, double lo, double hi) {
  Variable v;
  v.key = key;
  v.lower = lo;
  v.upper = hi;
  return v;
}

TEST(DesignSpace, LinearMapsEndsAndCentre) {
  const DesignSpace space({Linear("a", 2.0, 6.0)});
  EXPECT_DOUBLE_EQ(space.ToDesign({0.0}).at("a"), 2.0);
  EXPECT_DOUBLE_EQ(space.ToDesign({0.5}).at("a"), 4.0);
  EXPECT_DOUBLE_EQ(space.ToDesign({1.0}).at("a"), 6.0);
  EXPECT_DOUBLE_EQ(space.ToDesign({1.7}).at("a"), 6.0);  // clamped
  EXPECT_DOUBLE_EQ(space.ToUnit({{"a", 3.0}})[0], 0.25);
}

TEST(DesignSpace, LogIsGeometric) {
  Variable v = Linear("thickness_um", 10.0, 1000.0);
  v.log = true;
  const DesignSpace space({v});
  EXPECT_NEAR(space.ToDesign({0.5}).at("thickness_um"), 100.0, 1e-9);
  EXPECT_NEAR(space.ToUnit({{"thickness_um", 100.0}})[0], 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(space.ToDesign({1.0}).at("thickness_um"), 1000.0);
}

TEST(DesignSpace, IntegersGetEqualBins) {
  Variable v = Linear("n", 1.0, 4.0);
  v.integer = true;
  const DesignSpace space({v});
  int counts[5] = {};
  for (int i = 0; i < 400; ++i) {
    const double value = space.ToDesign({(i + 0.5) / 400.0}).at("n");
    ASSERT_EQ(value, std::round(value));
    ++counts[static_cast<int>(value)];
  }
  for (int k = 1; k <= 4; ++k) EXPECT_EQ(counts[k], 100) << k;
  EXPECT_DOUBLE_EQ(space.ToDesign({space.ToUnit({{"n", 3.0}})[0]}).at("n"), 3.0);
}

TEST(DesignSpace, StartPointUsesStartOrCentre) {
  Variable a = Linear("a", 0.0, 10.0);
  a.start = 2.0;
  const DesignSpace space({a, Linear("b", 0.0, 1.0)});
  const auto u = space.StartPoint();
  EXPECT_DOUBLE_EQ(u[0], 0.2);
  EXPECT_DOUBLE_EQ(u[1], 0.5);
}

TEST(DesignSpace, RejectsBadVariables) {
  EXPECT_THROW(DesignSpace({Linear("a", 1.0, 1.0)}), InputError);
  Variable log = Linear("a", 0.0, 1.0);
  log.log = true;
  EXPECT_THROW(DesignSpace({log}), InputError);
  Variable integer = Linear("a", 0.5, 3.0);
  integer.integer = true;
  EXPECT_THROW(DesignSpace({integer}), InputError);
  EXPECT_THROW(DesignSpace({Linear("a", 0, 1), Linear("a", 0, 2)}), InputError);
  const DesignSpace space({Linear("a", 0.0, 1.0)});
  EXPECT_THROW(space.ToUnit({{"a", 2.0}}), InputError);
  EXPECT_THROW(space.ToUnit({{"b", 0.5}}), InputError);
}

}  // namespace
}  // namespace fibrenet::optimizer
