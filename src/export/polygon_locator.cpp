#include "export/polygon_locator.h"

#include <cmath>
#include <limits>

namespace rad {

namespace {

// Triangles merged into one flat surface face the same way to within float rounding; the
// threshold (about 8 degrees) also keeps a tessellated curve's neighbours apart.
constexpr float kSameFacing = 0.99f;

// How far x lies from triangle c (its plane's normal n, unit) measured in its plane, as a
// distance outside its nearest edge (0 inside), and how far from its plane.
std::pair<float, float> distances(const std::array<Vec3, 3>& c, const Vec3& n, const Vec3& x) {
  const float plane = std::abs(glm::dot(x - c[0], n));
  float outside = 0.0f;
  for (int k = 0; k < 3; ++k) {
    const Vec3& a = c[size_t(k)];
    const Vec3& b = c[size_t((k + 1) % 3)];
    const Vec3 inward = glm::cross(n, b - a);  // points into the triangle for a front face
    const float len = glm::length(inward);
    if (!(len > 0.0f)) continue;
    outside = std::max(outside, -glm::dot(x - a, inward) / len);
  }
  return {plane, outside};
}

}  // namespace

PolygonLocator::PolygonLocator(const Triangles& t, const Aabb& bounds) : triangles_(&t) {
  // A hit point is computed in float from an eye that may lie far off: allow some thousand
  // roundings of the scene's magnitude.
  tolerance_ = std::max(bounds.magnitude() * 1e-4f, std::numeric_limits<float>::min());
  std::vector<Aabb> boxes(t.size());
  std::vector<Vec3> centres(t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    for (const Vec3& p : t.corners[i]) boxes[i].extend(p);
    boxes[i].lo -= Vec3(tolerance_), boxes[i].hi += Vec3(tolerance_);
    centres[i] = t.centroid(i);
  }
  tree_ = make_box_tree(boxes, centres, 4);
}

int32_t PolygonLocator::locate(const Vec3& x, const Vec3& front,
                               std::vector<std::pair<uint32_t, int>>& stack) const {
  const Triangles& t = *triangles_;
  // The surface met lies in the plane of the triangles it was merged from: a triangle beside
  // it across an edge (the side of a box beside its top) passes within the tolerance of a
  // point near that edge, but faces another way.
  const float length = glm::length(front);
  if (!(length > 0.0f)) return -1;
  const Vec3 facing = front / length;
  int32_t best = -1;
  float best_score = tolerance_;
  if (tree_.size() == 0) return best;
  auto inside_box = [&](const Aabb& b) {
    return x.x >= b.lo.x && x.x <= b.hi.x && x.y >= b.lo.y && x.y <= b.hi.y && x.z >= b.lo.z &&
           x.z <= b.hi.z;
  };
  walk_box_tree(
      tree_, 0, 0, stack, [&](uint32_t node, int&) { return inside_box(tree_.box[node]); },
      [&](uint32_t node) {
        for (uint32_t i = tree_.first[node]; i < tree_.first[node] + tree_.count[node]; ++i) {
          const uint32_t k = tree_.order[i];
          if (!(glm::dot(t.normal[k], facing) > kSameFacing)) continue;
          const auto [plane, outside] = distances(t.corners[k], t.normal[k], x);
          const float score = std::max(plane, outside);
          if (score < best_score || (score == best_score && (best < 0 || int32_t(k) < best))) {
            best_score = score, best = int32_t(k);
          }
        }
      });
  return best;
}

}  // namespace rad
