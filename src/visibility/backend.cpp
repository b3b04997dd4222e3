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

void VisibilityBackend::first_hits(std::span<const Segment> segments, std::span<SegmentHit> out,
                                   VisibilityStats& stats) const {
  assert(out.size() == segments.size());
  for (size_t i = 0; i < segments.size(); ++i) out[i] = first_hit(segments[i], stats);
}

}  // namespace rad
