// Deterministic random numbers for the reference renderer: PCG32 streams seeded by SplitMix64.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/math.h"

namespace rad {

/// One step of the splitmix64 sequence (core/math.h) started at `state`: the mix of the current
/// state, then the state moves on. Turns a (seed, index) pair into well-spread generator seeds.
inline uint64_t splitmix64_next(uint64_t& state) {
  const uint64_t out = splitmix64(state);
  state += 0x9E3779B97F4A7C15ull;
  return out;
}

/// PCG32 (O'Neill 2014, pcg32 "XSH RR"): a small, fast generator whose stream is fixed by its
/// seed and stream id, so every reference point draws the same numbers on any thread.
class Pcg32 {
 public:
  /// The generator for item `index` of a run seeded by `seed` (independent streams per index).
  Pcg32(uint64_t seed, uint64_t index) {
    uint64_t s = seed ^ (index * 0xD1B54A32D192ED03ull);
    const uint64_t init = splitmix64_next(s);
    inc_ = (splitmix64_next(s) << 1u) | 1u;
    state_ = 0;
    next();
    state_ += init;
    next();
  }

  uint32_t next() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31u));
  }

  /// Uniform in [0, 1), 32 random bits; or the next of the values given to draw_first.
  double uniform() {
    if (first_left_ > 0) {
      --first_left_;
      return *first_++;
    }
    return double(next()) * 0x1p-32;
  }

  /// The next `count` calls of uniform() return `values` (in [0, 1)) in order, then the stream
  /// goes on: a caller's stratified numbers for a path's first dimensions (the camera
  /// reference). `values` must outlive those calls.
  void draw_first(const double* values, size_t count) {
    first_ = values;
    first_left_ = count;
  }

 private:
  uint64_t state_ = 0;
  uint64_t inc_ = 1;
  const double* first_ = nullptr;
  size_t first_left_ = 0;
};

}  // namespace rad
