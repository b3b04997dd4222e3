#include "mesh/output_faces.h"

#include <gtest/gtest.h>

#include "mesh/subdivide.h"
#include "mesh_fixtures.h"

namespace rad {
namespace {

std::vector<Vec3> positions_with_centroids(const PolygonMesh& p, const PolygonFaces& f) {
  std::vector<Vec3> pos = p.positions;
  for (const auto& c : f.centroids)
    pos.push_back((p.positions[c[0]] + p.positions[c[1]] + p.positions[c[2]]) / 3.0f);
  return pos;
}

TEST(OutputFaces, UnsplitPolygonIsOneFace) {
  const PolygonMesh p = testing::one_polygon();
  const PolygonFaces f = triangulate_leaves(p);
  EXPECT_EQ(f.triangles, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_TRUE(f.centroids.empty());
}

// Faces tile the polygon exactly (same total area, same orientation, none degenerate) and no
// vertex lies strictly inside a face's edge: no T-junction, hence no crack.
TEST(OutputFaces, FacesTileThePolygonWithoutTJunctions) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    PolygonMesh p = testing::one_polygon({0, 0, 0}, {1, 0, 0}, {0.3f, 0.9f, 0});
    testing::split_randomly(p, int(seed * 3), seed);
    const PolygonFaces f = triangulate_leaves(p);
    const auto pos = positions_with_centroids(p, f);
    double area = 0.0;
    for (size_t t = 0; t < f.triangles.size(); t += 3) {
      const Vec3 a = pos[f.triangles[t]], b = pos[f.triangles[t + 1]], c = pos[f.triangles[t + 2]];
      const float z = glm::cross(b - a, c - a).z;
      ASSERT_GT(z, 1e-9f) << "degenerate or flipped face, seed " << seed;
      area += 0.5 * z;
      const Vec3 edge[3][2] = {{a, b}, {b, c}, {c, a}};
      for (const Vec3& q : pos) {
        for (const auto& e : edge) {
          const Vec3 d = e[1] - e[0];
          const float t_on = glm::dot(q - e[0], d) / glm::dot(d, d);
          const float off = glm::length(glm::cross(d, q - e[0])) / glm::length(d);
          EXPECT_FALSE(t_on > 1e-4f && t_on < 1.0f - 1e-4f && off < 1e-6f)
              << "T-junction, seed " << seed;
        }
      }
    }
    EXPECT_NEAR(area, p.elements[0].area, 1e-5);
  }
}

// Two triangles sharing the edge (1,0)-(0,1): the first splits twice, the second not at all. The
// second's faces take the first's midpoints on that edge as T-vertices (seam), in order, so
// the two tile the square without a crack there.
TEST(OutputFaces, ANeighboursMidpointsOnTheSharedEdgeAreSeamVertices) {
  PolygonMesh a = testing::one_polygon({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const PolygonMesh b = testing::one_polygon({1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  NewMidpoint created[3];
  split_element(a, 0, created);
  split_element(a, uint32_t(a.elements[0].first_child + 3), created);  // the middle child
  split_element(a, uint32_t(a.elements[0].first_child + 1), created);  // at corner (1,0)
  SeamVertices seams;
  for (uint32_t v = 0; v < a.vertex_count(); ++v) seams.add(a.positions[v], {0, v});
  for (uint32_t v = 0; v < b.vertex_count(); ++v) seams.add(b.positions[v], {1, v});
  const PolygonFaces f = triangulate_leaves(b, 1, &seams);
  // On the edge: its midpoint (0.5, 0.5) and the quarter point (0.75, 0.25), both a's.
  ASSERT_EQ(f.seam.size(), 2u);
  std::vector<Vec3> pos = positions_with_centroids(b, f);
  for (const VertexRef& r : f.seam) {
    EXPECT_EQ(r.polygon, 0u);
    pos.push_back(a.positions[r.vertex]);
  }
  double area = 0.0;
  for (size_t t = 0; t < f.triangles.size(); t += 3) {
    const Vec3 p0 = pos[f.triangles[t]], p1 = pos[f.triangles[t + 1]], p2 = pos[f.triangles[t + 2]];
    const float z = glm::cross(p1 - p0, p2 - p0).z;
    ASSERT_GT(z, 1e-9f) << "degenerate or flipped face";
    area += 0.5 * z;
  }
  EXPECT_NEAR(area, 0.5, 1e-6);
  EXPECT_EQ(f.triangles.size(), 9u);  // a fan of three from the corner (1,1)
  // Without the seams: the one face.
  EXPECT_EQ(triangulate_leaves(b, 1).triangles.size(), 3u);
}

}  // namespace
}  // namespace rad
