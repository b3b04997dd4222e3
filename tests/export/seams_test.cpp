#include "export/seams.h"

#include <gtest/gtest.h>

#include "mesh_parts.h"

namespace rad {
namespace {

// Two coplanar triangles sharing the edge (0,0,0)-(1,0,0): polygon 0 split along it with a
// bump at the middle, polygon 1 not split. The seam is the bump's height.
TEST(Seams, MeasuresTheJumpAcrossAnEdgeSharedWithAnUnsplitNeighbour) {
  Triangles t;
  t.corners = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
               {Vec3(1, 0, 0), Vec3(0, 0, 0), Vec3(0, -1, 0)}};
  t.normal = {Vec3(0, 0, 1), Vec3(0, 0, 1)};
  t.area = {0.5f, 0.5f};
  t.object = {0, 0};
  testing::MeshParts m;
  // Polygon 0: corners 0, 1, 2 and the edge's midpoint 3.
  m.position = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5f, 0, 0}, {1, 0, 0}, {0, 0, 0}, {0, -1, 0}};
  m.radiosity = {Vec3(1), Vec3(1), Vec3(1), Vec3(1.5f, 1.25f, 1), Vec3(1), Vec3(1), Vec3(1)};
  m.display = m.radiosity;
  m.indices = {0, 3, 2, 3, 1, 2, 4, 5, 6};
  m.face_polygon = {0, 0, 1};
  const SeamReport r = measure_seams(m.view(), t);
  EXPECT_EQ(r.shared_edges, 1u);
  EXPECT_EQ(r.vertices_checked, 5u);  // three on polygon 0's side, two on polygon 1's
  EXPECT_FLOAT_EQ(float(r.largest_jump), 0.5f);
  EXPECT_FLOAT_EQ(r.where.x, 0.5f);
  EXPECT_NEAR(r.mean_jump, 0.5 / 5, 1e-6);
}

TEST(Seams, IgnoresEdgesBetweenPolygonsThatAreNotCoplanar) {
  Triangles t;
  t.corners = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
               {Vec3(1, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 1)}};
  t.normal = {Vec3(0, 0, 1), Vec3(0, 1, 0)};
  t.area = {0.5f, 0.5f};
  t.object = {0, 0};
  testing::MeshParts m;
  m.position = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 0}, {0, 0, 1}};
  m.radiosity = {Vec3(1), Vec3(1), Vec3(1), Vec3(5), Vec3(5), Vec3(5)};
  m.display = m.radiosity;
  m.indices = {0, 1, 2, 3, 4, 5};
  m.face_polygon = {0, 1};
  EXPECT_EQ(measure_seams(m.view(), t).shared_edges, 0u);
}

}  // namespace
}  // namespace rad
