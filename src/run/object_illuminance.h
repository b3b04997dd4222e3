// What a lighting designer checks first: the light arriving on each object, least, mean and
// most, in lux when the scene is lit by photometric lights in metres.
#pragma once

#include <string>
#include <vector>

#include "solver/solver_state.h"

namespace rad {

/// One Pure's illuminance: of the luminance (Rec. 709 weights) of the light arriving H at its
/// vertices, the least and the most, and the mean over its area (each leaf element's corners).
struct ObjectIlluminance {
  int32_t object = -1;
  std::string name;
  double area = 0.0;
  double min = 0.0, mean = 0.0, max = 0.0;
};

/// Every Pure with area, in object order; areas in square metres with `metres_per_unit` metres
/// to a scene unit (--unit, run/scene_unit.h).
std::vector<ObjectIlluminance> object_illuminance(const SolverState& s,
                                                  double metres_per_unit = 1.0);

/// A table of the `rows` largest objects by area (all when fewer), with a title line.
std::string format_illuminance(const std::vector<ObjectIlluminance>& objects, size_t rows);

}  // namespace rad
