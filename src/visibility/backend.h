// The visibility interface the solver calls: batch occlusion of shadow segments, chosen at
// run time among the Embree BVH, the in-house voxel grid (design §6) and brute force.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string_view>

#include "hierarchy/hierarchy.h"
#include "visibility/segment.h"

namespace rad {

enum class BackendKind : uint8_t { Embree, Grid, Brute };

const char* to_string(BackendKind kind);
/// "embree" | "grid" | "brute"; throws rad::Error otherwise.
BackendKind parse_backend_kind(std::string_view name);

/// Ray statistics, as the original printed them plus backend-specific counts. Each thread keeps
/// its own and they are summed after the parallel loop.
struct VisibilityStats {
  uint64_t rays = 0;            // segments tested
  uint64_t occluded = 0;        // segments found blocked ("hits on polygons")
  uint64_t box_trials = 0;      // object bounding boxes tested (grid backend)
  uint64_t box_hits = 0;        // ... and hit
  uint64_t cells_visited = 0;   // voxels walked (grid backend)
  uint64_t triangle_tests = 0;  // ray-triangle tests (grid and brute backends)

  VisibilityStats& operator+=(const VisibilityStats& o) {
    rays += o.rays;
    occluded += o.occluded;
    box_trials += o.box_trials;
    box_hits += o.box_hits;
    cells_visited += o.cells_visited;
    triangle_tests += o.triangle_tests;
    return *this;
  }
};

/// The first surface a segment meets (VisibilityBackend::first_hit).
struct SegmentHit {
  bool hit = false;
  float t = 1.0f;     // where: origin + t * direction, in (0, 1)
  Vec3 normal{0.0f};  // its front side's normal, not normalised (the backends trace merged
                      // surfaces, not the scene's own triangles: no index is given)
};

struct VisibilityOptions {
  /// Trace batches as coherent packets where the backend can (Embree: rtcOccluded16); else one
  /// ray at a time. Answers are identical either way.
  bool packets = true;
};

/// Answers shadow-ray queries over a fixed set of triangles. Immutable after construction and
/// safe to call from many threads at once.
class VisibilityBackend {
 public:
  virtual ~VisibilityBackend() = default;
  virtual BackendKind kind() const = 0;
  /// For each segment, out[i] = 1 if a triangle blocks it, else 0. out.size() == segments.size().
  /// `stats` is the calling thread's own record: the call adds to it.
  virtual void occluded(std::span<const Segment> segments, std::span<uint8_t> out,
                        VisibilityStats& stats) const = 0;
  /// The same for the segments of a fan, out.size() == fan.size: a backend that can trace
  /// straight from the arrays overrides it (Embree fills its packets without the Segment
  /// copies); the default makes the segments, a chunk at a time on the stack, for occluded().
  virtual void occluded_fan(const SegmentFan& fan, std::span<uint8_t> out,
                            VisibilityStats& stats) const;
  /// The surface the segment meets first: of the triangles the shared test
  /// (segment_hit_distance in triangle_test.h) meets, the one at the least t (the first of the
  /// backends' common triangle order among equals); so every backend gives the same answer. For the
  /// few segments that need to know what they meet (where a buried vertex gathers), not for shadow
  /// rays: it may visit every triangle along the way.
  virtual SegmentHit first_hit(const Segment& segment, VisibilityStats& stats) const = 0;
  /// first_hit of each segment, out[i] for segments[i] (out.size() == segments.size()): the
  /// camera rays of a final render, a batch per call. The backends override it with a loop
  /// that calls their own first_hit directly; the default calls first_hit through the
  /// interface.
  virtual void first_hits(std::span<const Segment> segments, std::span<SegmentHit> out,
                          VisibilityStats& stats) const;
};

/// Builds the chosen backend over the hierarchy's triangles (the grid backend also uses its
/// objects). Throws rad::Error if the backend cannot be built (e.g. an Embree device error).
std::unique_ptr<VisibilityBackend> make_visibility_backend(BackendKind kind, const Hierarchy& h,
                                                           const VisibilityOptions& options = {});

}  // namespace rad
