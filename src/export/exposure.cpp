#include "export/exposure.h"

#include <algorithm>

namespace rad {

ToneMap scene_tone_map(const SolverState& s, const std::vector<Vec3>& display, ToneCurve curve,
                       float stops) {
  float brightest = 0.0f;
  for (const Material& m : s.solution.materials)
    brightest = std::max(brightest, max_component(m.emission));
  // Light sources are ignored, unless nothing else is left (every surface emits: a furnace).
  float ignore_above = brightest > 0.0f ? 0.5f * brightest : 1e30f;
  if (std::none_of(display.begin(), display.end(),
                   [&](const Vec3& c) { return max_component(c) <= ignore_above; })) {
    ignore_above = 1e30f;
  }
  ToneMap tm;
  tm.curve = curve;
  tm.scale = auto_exposure(display, ignore_above, stops);
  return tm;
}

}  // namespace rad
