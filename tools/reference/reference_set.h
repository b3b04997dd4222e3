// Reference points on a scene's triangles, the radiosity estimated there, and the CSV files
// that hold them (scenes/reference/).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/math.h"

namespace rad {

/// A point on triangle `triangle` (= rad's polygon id): position = a + u (b - a) + v (c - a).
struct ReferencePoint {
  int32_t triangle = 0;
  float u = 0.0f, v = 0.0f;
  Vec3 position{0.0f};
  Vec3 normal{0.0f};  // the triangle's front normal (unit); not stored in the CSV
};

/// Radiosity B = E + rho H at a point (exitance units, like rad's), with the standard error of
/// the estimate per channel and the number of path samples behind it.
struct ReferenceValue {
  DVec3 radiosity{0.0};
  DVec3 standard_error{0.0};
  uint64_t samples = 0;
};

struct ReferenceSet {
  std::vector<std::string> comments;  // written as "# ..." lines at the top
  std::vector<ReferencePoint> points;
  std::vector<ReferenceValue> values;  // one per point
};

/// Writes "# comment" lines, the header
/// `triangle,u,v,x,y,z,B_r,B_g,B_b,stderr_r,stderr_g,stderr_b`, then one row per point.
void write_reference_csv(std::ostream& out, const ReferenceSet& set);

/// Reads what write_reference_csv wrote (comments kept; normals left zero, samples 0).
/// Throws rad::Error naming `name`:line on a malformed row.
ReferenceSet read_reference_csv(std::istream& in, const std::string& name);

/// Same, from a file. Throws rad::Error if it cannot be read.
ReferenceSet read_reference_csv_file(const std::string& path);

}  // namespace rad
