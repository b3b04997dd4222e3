// Shadow-ray answers kept from one shot of a cluster to its next, which casts the same rays.
#pragma once

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "mesh/patch_mesh.h"
#include "solver/shot_source.h"

namespace rad {

/// One cluster's shadow-ray answers, kept for its next shot. A closed room shoots its walls again
/// and again (each time with what the furniture and the other walls sent back), and each shot of
/// a wall casts the same rays as the last: the receiving vertices, the samples' strata and which
/// samples face a vertex are geometry; only where a stratum's ray ends (its point nearest the
/// centroid of its unshot power) may move. So each vertex keeps one answer per sample, and a shot
/// traces only the samples whose end moved since the vertex was last traced, and the vertices
/// never traced (new ones, or skipped by the intensity cut). Every backend's answer is a function
/// of the segment alone (visibility/backend.h), so the radiosity is bit for bit that of tracing
/// every ray.
struct KeptRays {
  uint32_t epoch = 0;                      // shots of the cluster since its answers were kept
  uint32_t words = 0;                      // 64-bit words of answers per vertex
  std::vector<float> end_x, end_y, end_z;  // per sample: where its rays ended at the last shot
  std::vector<uint32_t> moved;             // per sample: the epoch its end last moved
  std::vector<uint32_t> receivers;         // the polygons that received, in order
  /// Per receiver, per vertex, 1 + words: the epoch the vertex was last traced (0: never), then
  /// one bit per sample, set where its ray was blocked.
  std::vector<std::vector<uint64_t>> answers;
  size_t bytes = 0;  // what its vectors hold
};

/// One vertex's kept answers, as gather_from_source reads and writes them.
struct VertexRays {
  uint64_t* record = nullptr;       // [epoch traced, blocked bits...]
  uint32_t epoch = 0;               // this shot's
  const uint32_t* moved = nullptr;  // per sample: the epoch its end last moved
};

/// A cluster's answers are kept once it shoots again within this many shots of its last shot.
/// A room's walls shoot every few tens of shots (the generated furnished room: each of its 10
/// big clusters about every 20), a building's clusters once or twice in thousands of shots (the
/// 1M-triangle building: 3,543 shots of 99k clusters in 600 s): kept from any third shot on,
/// its answers would fill 512 MiB and never be used.
inline constexpr uint64_t kKeptWithin = 64;

/// Every cluster's kept answers, and when each last shot.
struct KeptRayStore {
  std::unordered_map<int32_t, KeptRays> clusters;  // per cluster shot often enough
  size_t bytes = 0;                                // what they hold in all
  std::vector<uint64_t> last_shot;                 // per cluster: its last shot's number, 0: none
};

/// The kept answers for shot number `shot` (1-based), of `src` to `receivers` (polygons of
/// `mesh`, in index order), made ready (sized for every receiving vertex, the moved ends marked),
/// or null: unless the cluster shot within kKeptWithin shots before (or has answers kept
/// already), or when the answers kept would exceed `max_bytes`. Records the shot in
/// store.last_shot (sized for `cluster_count` clusters) either way.
KeptRays* prepare_kept_rays(KeptRayStore& store, const ShotSource& src, uint64_t shot,
                            std::span<const uint32_t> receivers, const Mesh& mesh,
                            size_t cluster_count, size_t max_bytes);

/// Vertex v of receiver i (its index in the list the answers were prepared for) in `kept`.
inline VertexRays vertex_rays(KeptRays& kept, size_t i, uint32_t v) {
  return {kept.answers[i].data() + size_t(v) * (1 + kept.words), kept.epoch, kept.moved.data()};
}

}  // namespace rad
