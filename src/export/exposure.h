// The display exposure of a solved scene, shared by mesh colours and rendered images.
#pragma once

#include "export/output_mesh.h"
#include "export/tonemap.h"

namespace rad {

/// The tone map for the mesh's display colours: automatic exposure (auto_exposure) over the
/// display values, ignoring those brighter than half the brightest emission (the light sources)
/// unless that leaves none, plus `stops`, followed by `curve`.
ToneMap scene_tone_map(const SolverState& s, const std::vector<Vec3>& display, ToneCurve curve,
                       float stops);

}  // namespace rad
