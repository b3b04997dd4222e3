// A cut-out surface solves as the same surface cut as polygons: shadow rays pass its holes, and
// it receives, reflects and shoots only on its opaque part.
#include <gtest/gtest.h>

#include "scene_builder.h"
#include "solver/texture_factors.h"
#include "visibility/backend.h"

namespace rad {
namespace {

Hierarchy room(bool cut) { return build_hierarchy(cutout_room(cut)); }

// Radiosity (or irradiance, `arriving`) integrated over the Pure `name`, in a 4 x 4 grid of
// bins over x and z.
std::vector<DVec3> integral(const Hierarchy& h, const SolverState& s, const std::string& name,
                            bool arriving) {
  std::vector<DVec3> bins(16, DVec3(0.0));
  for (size_t p = 0; p < h.triangles.size(); ++p) {
    if (h.objects[size_t(h.triangles.object[p])].name != name) continue;
    const PolygonMesh& m = s.solution.mesh.polygons[p];
    for_each_leaf(m, [&](uint32_t e) {
      const Element& el = m.elements[e];
      auto value = [&](uint32_t v) {
        return arriving ? s.solution.vertex_states[p][v].irradiance : s.solution.radiosity(p, v);
      };
      const Vec3 c = (m.positions[el.v[0]] + m.positions[el.v[1]] + m.positions[el.v[2]]) / 3.0f;
      const size_t bin =
          size_t(std::clamp(int(c.x * 4), 0, 3) * 4 + std::clamp(int(c.z * 4), 0, 3));
      bins[bin] +=
          DVec3(value(el.v[0]) + value(el.v[1]) + value(el.v[2])) * (double(el.area) / 3.0);
    });
  }
  return bins;
}

DVec3 sum(const std::vector<DVec3>& v) {
  DVec3 s(0.0);
  for (const DVec3& x : v) s += x;
  return s;
}

TEST(Cutouts, ACutOutLeafSolvesAsTheLeafCutAsPolygons) {
  const Hierarchy cut = room(true), polygons = room(false);
  const auto vc = make_visibility_backend(BackendKind::Embree, cut);
  const auto vp = make_visibility_backend(BackendKind::Embree, polygons);
  const SolverState a = testing::solve_shots(cut, *vc, SolverOptions{}, 300);
  const SolverState b = testing::solve_shots(polygons, *vp, SolverOptions{}, 300);
  // The floor: the leaf's shadow is the half's, bin by bin, in the light arriving.
  const auto floor_a = integral(cut, a, "floor", true),
             floor_b = integral(polygons, b, "floor", true);
  const DVec3 floor_total = sum(floor_b);
  for (size_t i = 0; i < 16; ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(floor_a[i][k], floor_b[i][k], 0.005 * floor_total[k] / 16) << "bin " << i;
    }
  }
  // The leaf reflects from its opaque half only, and the room takes that light alike.
  const DVec3 leaf_a = sum(integral(cut, a, "leaf", false));
  const DVec3 leaf_b = sum(integral(polygons, b, "leaf", false));
  const DVec3 ceiling_a = sum(integral(cut, a, "ceiling", false));
  const DVec3 ceiling_b = sum(integral(polygons, b, "ceiling", false));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(leaf_a[k] / leaf_b[k], 1.0, 0.005) << "channel " << k;
    EXPECT_NEAR(ceiling_a[k] / ceiling_b[k], 1.0, 0.005) << "channel " << k;
  }
}

}  // namespace
}  // namespace rad
