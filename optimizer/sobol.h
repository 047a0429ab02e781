// Sobol low-discrepancy sequence in up to kMaxDimensions dimensions, with the direction numbers
// of S. Joe and F. Y. Kuo, "Constructing Sobol sequences with better two-dimensional
// projections", SIAM J. Sci. Comput. 30 (2008) 2635-2654 (file new-joe-kuo-6.21201, first
// 31 rows), generated in Gray-code order (Antonov and Saleev 1979).
//
// Point 0 is the origin; the first 2^m points (m >= 0) of every dimension fill the 2^m
// intervals [k / 2^m, (k + 1) / 2^m) exactly once. The design-of-experiments sweep skips the
// origin (see optimizer/doe.h).
#pragma once

#include <cstdint>
#include <vector>

namespace fibrenet::optimizer {

class SobolSequence {
 public:
  static constexpr int kMaxDimensions = 32;
  static constexpr int kBits = 32;

  // Throws fibrenet::InputError unless 1 <= dimensions <= kMaxDimensions.
  explicit SobolSequence(int dimensions);

  int dimensions() const { return dimensions_; }

  // The next point, in [0, 1)^dimensions; the first call returns point 0 (the origin).
  // Throws fibrenet::Error after 2^32 - 1 points.
  std::vector<double> Next();

  // Advances past `n` points without returning them.
  void Skip(std::uint64_t n);

 private:
  int dimensions_;
  std::uint64_t index_ = 0;                    // index of the next point
  std::vector<std::uint32_t> x_;               // current integer coordinates
  std::vector<std::vector<std::uint32_t>> v_;  // direction numbers V[d][k], k = 0..kBits-1
};

}  // namespace fibrenet::optimizer
