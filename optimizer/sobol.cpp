#include "optimizer/sobol.h"

#include <fmt/format.h>

#include <bit>

#include "engine/core/error.h"

namespace fibrenet::optimizer {
namespace {

// One row of the Joe-Kuo table: degree s of the primitive polynomial, its coefficients a
// (the inner bits, highest first) and the initial direction integers m_1..m_s (m_k odd,
// m_k < 2^k). Dimension 1 is the van der Corput sequence and has no row.
struct DirectionRow {
  int s;
  std::uint32_t a;
  std::uint32_t m[8];
};

// Dimensions 2 to 32 of new-joe-kuo-6.21201, row for row.
constexpr DirectionRow kJoeKuo[SobolSequence::kMaxDimensions - 1] = {
    {1, 0, {1}},                         // d = 2
    {2, 1, {1, 3}},                      // d = 3
    {3, 1, {1, 3, 1}},                   // d = 4
    {3, 2, {1, 1, 1}},                   // d = 5
    {4, 1, {1, 1, 3, 3}},                // d = 6
    {4, 4, {1, 3, 5, 13}},               // d = 7
    {5, 2, {1, 1, 5, 5, 17}},            // d = 8
    {5, 4, {1, 1, 5, 5, 5}},             // d = 9
    {5, 7, {1, 1, 7, 11, 19}},           // d = 10
    {5, 11, {1, 1, 5, 1, 1}},            // d = 11
    {5, 13, {1, 1, 1, 3, 11}},           // d = 12
    {5, 14, {1, 3, 5, 5, 31}},           // d = 13
    {6, 1, {1, 3, 3, 9, 7, 49}},         // d = 14
    {6, 13, {1, 1, 1, 15, 21, 21}},      // d = 15
    {6, 16, {1, 3, 1, 13, 27, 49}},      // d = 16
    {6, 19, {1, 1, 1, 15, 7, 5}},        // d = 17
    {6, 22, {1, 3, 1, 15, 13, 25}},      // d = 18
    {6, 25, {1, 1, 5, 5, 19, 61}},       // d = 19
    {7, 1, {1, 3, 7, 11, 23, 15, 103}},  // d = 20
    {7, 4, {1, 3, 7, 13, 13, 15, 69}},   // d = 21
    {7, 7, {1, 1, 3, 13, 7, 35, 63}},    // d = 22
    {7, 8, {1, 3, 5, 9, 1, 25, 53}},     // d = 23
    {7, 14, {1, 3, 1, 13, 9, 35, 107}},  // d = 24
    {7, 19, {1, 3, 1, 5, 27, 61, 31}},   // d = 25
    {7, 21, {1, 1, 5, 11, 19, 41, 61}},  // d = 26
    {7, 28, {1, 3, 5, 3, 3, 13, 69}},    // d = 27
    {7, 31, {1, 1, 7, 13, 1, 19, 1}},    // d = 28
    {7, 32, {1, 3, 7, 5, 13, 19, 59}},   // d = 29
    {7, 37, {1, 1, 3, 9, 25, 29, 41}},   // d = 30
    {7, 41, {1, 3, 5, 13, 23, 1, 55}},   // d = 31
    {7, 42, {1, 3, 7, 3, 13, 59, 17}},   // d = 32
};

// Direction numbers V_k = m_k 2^(32 - k) (k = 1..32) of one dimension, from the recurrence
// m_k = 2 a_1 m_{k-1} xor 4 a_2 m_{k-2} xor ... xor 2^s m_{k-s} xor m_{k-s}, written directly
// on the shifted V's (Bratley and Fox 1988, Joe and Kuo 2008).
std::vector<std::uint32_t> Directions(int dimension) {
  constexpr int kBits = SobolSequence::kBits;
  std::vector<std::uint32_t> v(kBits);
  if (dimension == 0) {
    for (int k = 0; k < kBits; ++k) v[k] = std::uint32_t{1} << (kBits - 1 - k);
    return v;
  }
  const DirectionRow& row = kJoeKuo[dimension - 1];
  const int s = row.s;
  for (int k = 0; k < s && k < kBits; ++k) v[k] = row.m[k] << (kBits - 1 - k);
  for (int k = s; k < kBits; ++k) {
    std::uint32_t value = v[k - s] ^ (v[k - s] >> s);
    for (int j = 1; j < s; ++j) {
      if ((row.a >> (s - 1 - j)) & 1U) value ^= v[k - j];
    }
    v[k] = value;
  }
  return v;
}

}  // namespace

SobolSequence::SobolSequence(int dimensions) : dimensions_(dimensions) {
  if (dimensions < 1 || dimensions > kMaxDimensions) {
    throw InputError(fmt::format("Sobol sequence: dimensions must lie in [1, {}]; got {}",
                                 kMaxDimensions, dimensions));
  }
  x_.assign(dimensions, 0);
  for (int d = 0; d < dimensions; ++d) v_.push_back(Directions(d));
}

std::vector<double> SobolSequence::Next() {
  if (index_ >= (std::uint64_t{1} << kBits) - 1) {
    throw Error("Sobol sequence: more than 2^32 - 1 points requested");
  }
  std::vector<double> point(dimensions_);
  for (int d = 0; d < dimensions_; ++d) point[d] = static_cast<double>(x_[d]) * 0x1.0p-32;
  // Gray-code step: point i + 1 differs from point i by the direction number of the lowest
  // zero bit of i.
  const int c = std::countr_one(index_);
  for (int d = 0; d < dimensions_; ++d) x_[d] ^= v_[d][c];
  ++index_;
  return point;
}

void SobolSequence::Skip(std::uint64_t n) {
  for (std::uint64_t i = 0; i < n; ++i) Next();
}

}  // namespace fibrenet::optimizer
