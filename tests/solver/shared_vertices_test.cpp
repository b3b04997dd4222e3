// Vertices shared within a planar cluster: one gathers, the others copy it.
#include "solver/shared_vertices.h"

#include <gtest/gtest.h>

#include <map>
#include <tuple>

#include "scene_builder.h"
#include "solver/solver_state.h"

namespace rad {
namespace {

TEST(SharedVertices, EachPlaceOfAPlanarClusterHasOneGathererTheLowestVertexThere) {
  SceneDescription d;
  // A floor cut into 3 x 3 quads (18 triangles, one planar cluster) and a lamp above it.
  testing::add_quad(d, "floor", Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, -1), Vec3(0, 0, -1),
                    Vec3(0.5f), Vec3(0.0f), 3);
  testing::add_quad(d, "lamp", Vec3(0.4f, 1, -0.4f), Vec3(0.6f, 1, -0.4f), Vec3(0.6f, 1, -0.6f),
                    Vec3(0.4f, 1, -0.6f), Vec3(0.0f), Vec3(1.0f));
  const Hierarchy h = build_hierarchy(d);
  const SolverState s = make_solver_state(h, SolverOptions{});
  const Mesh& mesh = s.solution.mesh;
  const Clusters& clusters = s.scene.clusters;
  const SharedVertices sh = find_shared_vertices(mesh, clusters);
  ASSERT_EQ(sh.copies.size(), mesh.polygons.size());

  // Every vertex of the floor by place: the lowest (polygon, vertex) there must gather and every
  // other one copy it.
  std::map<std::tuple<uint32_t, PositionBits>, std::pair<uint32_t, uint32_t>> lowest;
  size_t floor_vertices = 0;
  for (uint32_t p = 0; p < mesh.polygons.size(); ++p) {
    if (!shares_vertices(clusters, p)) continue;
    for (uint32_t v = 0; v < mesh.polygons[p].vertex_count(); ++v) {
      const auto place = shared_place(clusters, p, mesh.polygons[p].positions[v]);
      ASSERT_TRUE(place);
      lowest.try_emplace({place->cluster, place->position}, p, v);
      ++floor_vertices;
    }
  }
  size_t copies = 0;
  for (uint32_t p = 0; p < mesh.polygons.size(); ++p) {
    for (uint32_t v = 0; v < mesh.polygons[p].vertex_count(); ++v) {
      const auto place = shared_place(clusters, p, mesh.polygons[p].positions[v]);
      if (!place) {
        EXPECT_FALSE(sh.is_copy(p, v));
        continue;
      }
      const auto [gp, gv] = lowest.at({place->cluster, place->position});
      EXPECT_EQ(sh.is_copy(p, v), gp != p || gv != v) << p << " " << v;
    }
    for (const VertexCopy& c : sh.copies[p]) {
      ++copies;
      EXPECT_FALSE(sh.is_copy(c.from_polygon, c.from_vertex)) << "a copy's source is a copy";
      EXPECT_EQ(mesh.polygons[c.from_polygon].positions[c.from_vertex],
                mesh.polygons[p].positions[c.vertex]);
    }
  }
  EXPECT_EQ(copies, floor_vertices - lowest.size());
  EXPECT_GT(copies, 0u);
}

TEST(SharedVertices, OnTriangleEdgeHoldsForMidpointsOfEdgesOnly) {
  const std::array<Vec3, 3> c{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)};
  EXPECT_TRUE(on_triangle_edge(c, (c[0] + c[1]) * 0.5f));
  EXPECT_TRUE(on_triangle_edge(c, (c[1] + c[2]) * 0.5f));
  EXPECT_TRUE(on_triangle_edge(c, c[2]));
  EXPECT_FALSE(on_triangle_edge(c, (c[0] + c[1] + c[2]) / 3.0f));
  EXPECT_FALSE(on_triangle_edge(c, Vec3(0.01f, 0.01f, 0.0f)));
}

}  // namespace
}  // namespace rad
