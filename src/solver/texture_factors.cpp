#include "solver/texture_factors.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rad {

bool is_textured(const Triangles& t, size_t p, const SceneObject& o) {
  return (o.base_texture || o.emissive_texture || o.cutout) && p < t.uv.size() &&
         std::isfinite(t.uv[p][0].x);
}

TextureFactors texture_factor(const Triangles& t, size_t p, const SceneObject& o,
                              const Vec3& position, float element_area) {
  const std::array<Vec3, 3>& c = t.corners[p];
  const std::array<Vec2, 3>& uv = t.uv[p];
  // Barycentric coordinates by sub-triangle areas, in double: the position lies in the plane.
  const DVec3 a(c[0]), b(c[1]), d(c[2]), x(position);
  const DVec3 n = glm::cross(b - a, d - a);
  const double n2 = glm::dot(n, n);
  const double wb = glm::dot(glm::cross(x - a, d - a), n) / n2;
  const double wc = glm::dot(glm::cross(b - a, x - a), n) / n2;
  const double wa = 1.0 - wb - wc;
  const Vec2 at = Vec2(float(wa * uv[0].x + wb * uv[1].x + wc * uv[2].x),
                       float(wa * uv[0].y + wb * uv[1].y + wc * uv[2].y));
  // The element's area in the texture's unit square: the triangle maps its area to its texture
  // area affinely. Its footprint in an image is that times the image's texels.
  const double uv_area = 0.5 *
                         std::abs(double(uv[1].x - uv[0].x) * double(uv[2].y - uv[0].y) -
                                  double(uv[2].x - uv[0].x) * double(uv[1].y - uv[0].y)) *
                         double(element_area) / double(t.area[p]);
  auto width_in = [&](const TextureImage& image) {
    return float(std::sqrt(2.0 * uv_area * double(image.width()) * double(image.height())));
  };
  auto over_mean = [&](const TextureMap& texture) {
    Vec3 f(1.0f);
    if (!texture) return f;
    const TextureImage& image = *texture.image;
    const Vec4 s = sample_texture(texture, at, width_in(image));
    for (int k = 0; k < 3; ++k) {
      if (image.mean[k] > 0.0f) f[k] = s[k] / image.mean[k];
    }
    return f;
  };
  TextureFactors f{over_mean(o.base_texture), over_mean(o.emissive_texture)};
  if (o.cutout) {
    const float opaque = opaque_fraction(o.cutout, at, width_in(*o.cutout.texture.image));
    f.reflectance *= opaque, f.emission *= opaque;
  }
  return f;
}

std::vector<TextureFactors> initial_texture_factors(const Triangles& t, size_t p,
                                                    const SceneObject& o, const PolygonMesh& mesh) {
  std::vector<float> area(mesh.vertex_count(), std::numeric_limits<float>::max());
  for_each_leaf(mesh, [&](uint32_t e) {
    const Element& el = mesh.elements[e];
    for (const uint32_t v : el.v) area[v] = std::min(area[v], el.area);
  });
  std::vector<TextureFactors> f(mesh.vertex_count());
  for (size_t v = 0; v < f.size(); ++v) f[v] = texture_factor(t, p, o, mesh.positions[v], area[v]);
  return f;
}

}  // namespace rad
