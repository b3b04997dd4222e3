#include "reference/buried_points.h"

#include <cmath>
#include <limits>

namespace rad {

std::vector<uint8_t> buried_points(const RayScene& scene, const Triangles& triangles,
                                   const std::vector<ReferencePoint>& points, float offset) {
  std::vector<uint8_t> buried(points.size(), 0);
  const FlushDenormals ftz;
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3 n = triangles.normal[size_t(points[i].triangle)];  // the CSV keeps no normal
    const Vec3 origin = points[i].position + n * offset;
    // An orthonormal frame around n (Duff et al. 2017).
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
    const Vec3 t(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    const Vec3 s(b, sign + n.y * n.y * a, -n.y);
    bool inside = true;
    for (int k = 0; k < 7 && inside; ++k) {
      Vec3 dir = n;
      if (k > 0) {
        const float phi = float(k - 1) * 1.04719755f;  // 60 degrees apart
        dir = 0.5f * n + 0.8660254f * (std::cos(phi) * t + std::sin(phi) * s);
      }
      const RayHit hit = scene.intersect(origin, dir, std::numeric_limits<float>::infinity());
      inside = hit.triangle >= 0 && glm::dot(triangles.normal[size_t(hit.triangle)], dir) > 0.0f;
    }
    buried[i] = inside ? 1 : 0;
  }
  return buried;
}

}  // namespace rad
