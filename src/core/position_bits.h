// A position as the bits of its coordinates, -0 as +0: the key of exact welds (two points are
// one when they are the same floats), and the seed of the draws made at a point.
#pragma once

#include <array>
#include <bit>
#include <cstdint>

#include "core/math.h"

namespace rad {

using PositionBits = std::array<uint32_t, 3>;

inline PositionBits position_bits(const Vec3& p) {
  return {std::bit_cast<uint32_t>(p.x + 0.0f), std::bit_cast<uint32_t>(p.y + 0.0f),
          std::bit_cast<uint32_t>(p.z + 0.0f)};
}

/// FNV-1a over the words, after `seed` (a group the position belongs to, or 0).
inline size_t hash_position_bits(const PositionBits& k, uint32_t seed = 0) {
  uint64_t h = 1469598103934665603ull;
  h = (h ^ seed) * 1099511628211ull;
  for (uint32_t w : k) h = (h ^ w) * 1099511628211ull;
  return size_t(h);
}

/// 64 well-mixed bits of a position (its bits, -0 as +0, through mix64): the seed of the draws
/// made at a point (its penumbra rounds' ray ends, its roulette lot), so neighbouring points
/// draw differently and a point, and every polygon's copy of a shared vertex, always the same,
/// on any thread or rank.
inline uint64_t position_seed(const Vec3& p) {
  const PositionBits b = position_bits(p);
  return mix64(mix64(mix64(b[0]) ^ b[1]) ^ b[2]);
}

struct PositionBitsHash {
  size_t operator()(const PositionBits& k) const { return hash_position_bits(k); }
};

}  // namespace rad
