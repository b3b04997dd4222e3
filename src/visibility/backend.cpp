#include "visibility/backend.h"

#include <algorithm>
#include <cassert>

namespace rad {

void VisibilityBackend::occluded_fan(const SegmentFan& fan, std::span<uint8_t> out,
                                     VisibilityStats& stats) const {
  assert(out.size() == fan.size);
  constexpr size_t kChunk = 64;
  Segment chunk[kChunk];
  for (size_t begin = 0; begin < fan.size; begin += kChunk) {
    const size_t n = std::min(kChunk, fan.size - begin);
    for (size_t i = 0; i < n; ++i) chunk[i] = fan.segment(begin + i);
    occluded(std::span<const Segment>(chunk, n), out.subspan(begin, n), stats);
  }
}

}  // namespace rad
