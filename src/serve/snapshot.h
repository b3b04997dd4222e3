// An immutable picture of the solve between two shots: what every HTTP thread reads.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "export/output_mesh.h"
#include "export/tonemap.h"
#include "serve/material_controls.h"

namespace rad {

enum class SessionStatus : uint8_t { Running, Paused, Converged, Stopped };
const char* to_string(SessionStatus s);

/// Per hierarchy object: leaf elements below it, and (Pures) the controls of its material.
struct ObjectSnapshot {
  int64_t elements = 0;
  MaterialControls controls;
};

/// Built by the solver thread, then never changed: any thread may read it without locks.
struct Snapshot {
  uint64_t version = 0;       // grows by one per snapshot (colours, progress or geometry)
  uint64_t mesh_version = 0;  // grows when positions or faces change
  SessionStatus status = SessionStatus::Running;
  int64_t shots = 0;
  double unshot_fraction = 0.0;
  double rays_per_second = 0.0;
  double seconds = 0.0;        // solving time since the (re)start, pauses excluded
  double build_seconds = 0.0;  // how long the previous snapshot took to build
  int64_t elements = 0;        // leaf elements of every polygon
  // The solved view as `rad` writes it; its geometry is shared by successive snapshots while
  // subdivision adds nothing.
  OutputMesh mesh;
  std::vector<Vec3> colour;  // per vertex: tone_map(mesh.display, tone), display-referred linear
  ToneMap tone;
  float exposure_stops = 0.0f;                      // the user's offset, included in tone.scale
  bool exposure_locked = false;                     // tone.scale no longer follows the solve
  std::vector<ObjectSnapshot> objects;              // per hierarchy object
  std::vector<LightControls> lights;                // per light of the hierarchy, as applied
  std::vector<float> dimmers;                       // per light group: its factor in `colour`
  std::vector<std::pair<int64_t, double>> history;  // (shot, unshot fraction), at most ~256
  std::string notice;  // the outcome of the last edit, for the page ("" when none)
};

/// Leaf elements per object: polygons' leaf counts summed over each object's triangle range.
std::vector<int64_t> elements_per_object(const SolverState& s);

/// At most `limit` points of the convergence history, evenly thinned, always with the last one.
std::vector<std::pair<int64_t, double>> thin_history(const std::vector<ShotRecord>& h,
                                                     size_t limit);

}  // namespace rad
