#include "visibility/brute_backend.h"

#include <cassert>
#include <vector>

#include "visibility/triangle_test.h"

namespace rad {

namespace {

class BruteBackend final : public VisibilityBackend {
 public:
  explicit BruteBackend(const Hierarchy& h) : records_(make_triangle_records(h, &cutouts_)) {}

  BackendKind kind() const override { return BackendKind::Brute; }

  void occluded(std::span<const Segment> segments, std::span<uint8_t> out,
                VisibilityStats& stats) const override {
    assert(out.size() == segments.size());
    uint64_t blocked = 0, tests = 0;
    for (size_t i = 0; i < segments.size(); ++i) {
      const Segment& s = segments[i];
      uint8_t hit = 0;
      for (const TriangleRecord& r : records_) {
        ++tests;
        if (segment_blocked(r, cutouts_, s.origin, s.direction)) {
          hit = 1;
          break;
        }
      }
      out[i] = hit;
      blocked += hit;
    }
    stats.rays += segments.size();
    stats.occluded += blocked;
    stats.triangle_tests += tests;
  }

  void first_hits(std::span<const Segment> segments, std::span<SegmentHit> out,
                  VisibilityStats& stats) const override {
    for (size_t i = 0; i < segments.size(); ++i) out[i] = first_hit(segments[i], stats);
  }

  SegmentHit first_hit(const Segment& s, VisibilityStats& stats) const override {
    SegmentHitRecord best;
    for (uint32_t i = 0; i < uint32_t(records_.size()); ++i) {
      keep_nearer(best, segment_block_distance(records_[i], cutouts_, s.origin, s.direction), i);
    }
    stats.rays += 1;
    stats.triangle_tests += records_.size();
    stats.occluded += best.triangle != ~0u ? 1 : 0;
    return hit_of(best, records_);
  }

 private:
  Cutouts cutouts_;  // before records_, which names them
  std::vector<TriangleRecord> records_;
};

}  // namespace

std::unique_ptr<VisibilityBackend> make_brute_backend(const Hierarchy& h,
                                                      const VisibilityOptions& options) {
  return std::make_unique<BruteBackend>(h);
}

}  // namespace rad
