#include "export/exposure.h"

#include <algorithm>

namespace rad {

ToneMap scene_tone_map(const SolverState& s, const OutputMesh& mesh, ToneCurve curve, float stops) {
  float brightest = 0.0f;
  for (const Material& m : s.materials) brightest = std::max(brightest, max_component(m.emission));
  ToneMap tm;
  tm.curve = curve;
  tm.scale = auto_exposure(mesh.display, brightest > 0.0f ? 0.5f * brightest : 1e30f, stops);
  return tm;
}

}  // namespace rad
