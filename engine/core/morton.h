// Morton (Z-order) keys of tiles in the plane: tiles near each other get keys near each other,
// so data laid out in key order is read from nearby memory when nearby tiles meet.
#pragma once

#include <cstdint>

namespace fibrenet {

// Spreads the low 16 bits of v to the even bits of the result.
inline std::uint32_t SpreadBits(std::uint32_t v) {
  v &= 0xffffu;
  v = (v | (v << 8)) & 0x00ff00ffu;
  v = (v | (v << 4)) & 0x0f0f0f0fu;
  v = (v | (v << 2)) & 0x33333333u;
  v = (v | (v << 1)) & 0x55555555u;
  return v;
}

// The key of tile (tx, ty), each below 2^16.
inline std::uint32_t MortonKey(std::uint32_t tx, std::uint32_t ty) {
  return SpreadBits(tx) | (SpreadBits(ty) << 1);
}

}  // namespace fibrenet
