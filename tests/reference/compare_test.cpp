// Gouraud interpolation over rad's output faces at reference points, the error figures, and
// rad's PLY files read back.
#include "reference/compare.h"

#include <gtest/gtest.h>

#include <array>
#include <fstream>

#include "../export/mesh_parts.h"
#include "core/error.h"
#include "export/ply_writer.h"
#include "reference/ply_reader.h"
#include "reference/reference_points.h"

namespace rad {
namespace {

// Two polygons: the unit square at z = 0 (triangles 0 and 1) facing +z.
Hierarchy unit_square() {
  SceneDescription s;
  s.name = "square";
  ObjectDescription o;
  o.name = "square";
  o.material = {Vec3(0.5f), Vec3(0.0f)};
  o.triangles = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)},
                 {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}};
  s.objects = {o};
  s.roots = {0};
  return build_hierarchy(s);
}

Vec3 field(const Vec3& p) { return Vec3(1.0f + p.x, 2.0f + p.y, 3.0f + p.x - p.y); }

// Each polygon cut into four faces at its edge midpoints (vertices not shared across
// polygons, as rad writes them), radiosity = field at the vertices.
testing::MeshParts split_mesh(const Hierarchy& h) {
  testing::MeshParts m;
  for (size_t t = 0; t < h.triangles.size(); ++t) {
    const auto& c = h.triangles.corners[t];
    const uint32_t base = uint32_t(m.position.size());
    const Vec3 p[6] = {
        c[0], c[1], c[2], (c[0] + c[1]) * 0.5f, (c[1] + c[2]) * 0.5f, (c[2] + c[0]) * 0.5f};
    for (const Vec3& q : p) {
      m.position.push_back(q);
      m.radiosity.push_back(field(q));
      m.display.push_back(field(q));
    }
    for (uint32_t i : {0u, 3u, 5u, 3u, 1u, 4u, 5u, 4u, 2u, 3u, 4u, 5u})
      m.indices.push_back(base + i);
    m.face_polygon.insert(m.face_polygon.end(), 4, int32_t(t));
  }
  return m;
}

ShadedFacesView view(const testing::MeshParts& m) {
  return {m.position, m.radiosity, m.indices, m.face_polygon};
}

ReferenceSet reference_of(const Hierarchy& h, float scale) {
  ReferenceSet r;
  PointOptions o;
  o.total = 100;
  r.points = make_reference_points(h.triangles, o);
  for (const ReferencePoint& p : r.points) {
    ReferenceValue v;
    v.radiosity = DVec3(field(p.position)) * double(scale);
    v.standard_error = DVec3(0.01);
    r.values.push_back(v);
  }
  return r;
}

TEST(Compare, LinearFieldIsInterpolatedExactly) {
  const Hierarchy h = unit_square();
  const testing::MeshParts m = split_mesh(h);
  const ComparisonReport r = compare_to_reference(view(m), reference_of(h, 1.0f));
  EXPECT_EQ(r.all.points, 100u);
  EXPECT_EQ(r.outside, 0u);
  EXPECT_LT(r.all.mean_error, 1e-6);
  EXPECT_LT(r.all.worst_error, 1e-6);
  EXPECT_EQ(r.reflecting.points, 0u);  // no emitters named
  EXPECT_LT(r.largest_plane_distance, 1e-6);
}

TEST(Compare, ReportsRelativeErrorsPerChannelAndOverall) {
  const Hierarchy h = unit_square();
  const testing::MeshParts m = split_mesh(h);
  // The reference 2% brighter: rad is off by 1/1.02 - 1 of the reference everywhere.
  const ComparisonReport r = compare_to_reference(view(m), reference_of(h, 1.02f));
  const double expected = 1.0 - 1.0 / 1.02;
  EXPECT_NEAR(r.all.mean_error, expected, 1e-5);
  EXPECT_NEAR(r.all.mean_signed_error, -expected, 1e-5);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.all.channel_error[c], expected, 1e-5);
  EXPECT_GT(r.all.worst_error, expected);
  const DVec3& mean = r.all.mean_reference;
  EXPECT_NEAR(r.all.reference_noise, 0.01 / ((mean.x + mean.y + mean.z) / 3.0), 1e-9);
  EXPECT_FALSE(format_report(r).empty());
}

TEST(Compare, ATexturedPointIsItsTexelOverTheInterpolatedIrradiance) {
  const Hierarchy h = unit_square();
  const testing::MeshParts m = split_mesh(h);
  // Irradiance the field too; points of the first polygon textured, reflecting 0.25 and
  // emitting 0.1 where they are, the others as their vertices say.
  const ShadedFacesView faces{m.position, m.radiosity, m.indices, m.face_polygon, m.radiosity};
  ReferenceSet ref = reference_of(h, 1.0f);
  std::vector<TexelSurface> texels(ref.points.size());
  size_t textured = 0;
  for (size_t i = 0; i < ref.points.size(); ++i) {
    if (ref.points[i].triangle != 0) continue;
    texels[i] = {true, Vec3(0.25f), Vec3(0.1f)};
    ref.values[i].radiosity = 0.1 + 0.25 * DVec3(field(ref.points[i].position));
    ++textured;
  }
  ASSERT_GT(textured, 10u);
  const ComparisonReport r = compare_to_reference(faces, ref, {}, {}, texels);
  EXPECT_LT(r.all.worst_error, 1e-6);
  // Without the irradiance, the vertices' radiosity: the textured points are off.
  const ComparisonReport plain = compare_to_reference(view(m), ref, {}, {}, texels);
  EXPECT_GT(plain.all.worst_error, 0.1);
}

TEST(Compare, FiguresWithoutEmittersLeaveTheirPointsOut) {
  const Hierarchy h = unit_square();
  testing::MeshParts m = split_mesh(h);
  for (size_t v = 0; v < m.position.size() / 2; ++v) m.radiosity[v] *= 2.0f;  // polygon 0 off
  const std::vector<uint8_t> emitting = {1, 0};                               // ... but it "emits"
  const ComparisonReport r = compare_to_reference(view(m), reference_of(h, 1.0f), emitting);
  EXPECT_GT(r.all.mean_error, 0.1);
  EXPECT_EQ(r.reflecting.points + 50u, r.all.points);
  EXPECT_LT(r.reflecting.mean_error, 1e-6);
  EXPECT_EQ(emitting_polygons(h), std::vector<uint8_t>({0, 0}));
}

TEST(Compare, UsesOnlyFacesOfThePointsOwnPolygon) {
  const Hierarchy h = unit_square();
  testing::MeshParts m = split_mesh(h);
  for (size_t v = 0; v < m.position.size() / 2; ++v) m.radiosity[v] = Vec3(100.0f);  // polygon 0
  ReferenceSet ref = reference_of(h, 1.0f);
  const ComparisonReport r = compare_to_reference(view(m), ref);
  for (const PointComparison& c : r.per_point) {
    const double expected = c.triangle == 0 ? 100.0 : c.reference.x;
    EXPECT_NEAR(c.rad.x, expected, 1e-4) << "point " << c.index;
  }
}

TEST(Compare, MissingPolygonIsAnError) {
  const Hierarchy h = unit_square();
  testing::MeshParts m = split_mesh(h);
  m.indices.resize(m.indices.size() / 2);
  m.face_polygon.resize(m.face_polygon.size() / 2);
  EXPECT_THROW(compare_to_reference(view(m), reference_of(h, 1.0f)), Error);
}

// The polygons assign_face_polygons finds for faces on a scene of the one triangle abc, each
// face three points (u, v) of it, at a + u (b - a) + v (c - a) rounded to floats as rad writes
// them.
std::vector<int32_t> polygons_of_faces(const Vec3& a, const Vec3& b, const Vec3& c,
                                       const std::vector<std::array<glm::dvec2, 3>>& faces) {
  SceneDescription s;
  s.name = "triangle";
  ObjectDescription o;
  o.name = "triangle";
  o.material = {Vec3(0.5f), Vec3(0.0f)};
  o.triangles = {{a, b, c}};
  s.objects = {o};
  s.roots = {0};
  const Hierarchy h = build_hierarchy(s);
  std::vector<Vec3> position;
  std::vector<uint32_t> indices;
  for (const auto& face : faces) {
    for (const glm::dvec2& uv : face) {
      indices.push_back(uint32_t(position.size()));
      position.push_back(Vec3(DVec3(a) + uv.x * DVec3(b - a) + uv.y * DVec3(c - a)));
    }
  }
  return assign_face_polygons(h.triangles, position, indices);
}

// A tilted triangle 16 m from the origin, and faces of it a few micrometres across: its corners,
// rounded to floats there, tilt its normal and lift its centroid off the plane by more than a
// fixed fraction of its size, yet it lies on that triangle.
TEST(Compare, ASmallFaceFarFromTheOriginFindsItsPolygon) {
  const Vec3 at(16.2421f, -5.58674f, 10.1272f);
  std::vector<std::array<glm::dvec2, 3>> faces;
  for (int k = 0; k < 20; ++k) {
    const double u = 0.03 * k, v = 0.3;
    faces.push_back({glm::dvec2(u, v), glm::dvec2(u + 1e-5, v), glm::dvec2(u, v + 1e-5)});
  }
  EXPECT_EQ(
      polygons_of_faces(at, at + Vec3(0.7f, 0.31f, 0.05f), at + Vec3(0.13f, 0.52f, 0.61f), faces),
      std::vector<int32_t>(20, 0));
}

// Slivers of a turned triangle, each as high as a float's rounding there: their normals, from
// rounded corners, point anywhere, yet each lies on the triangle.
TEST(Compare, ASliverWhoseNormalIsRoundingFindsItsPolygon) {
  const Vec3 a(1.91f, 0.38f, 3.44f);
  std::vector<std::array<glm::dvec2, 3>> faces;
  for (int k = 0; k < 20; ++k) {
    const double v = 0.02 + 0.02 * k;
    faces.push_back({glm::dvec2(0.1, v), glm::dvec2(0.5, v), glm::dvec2(0.3, v + 2e-7)});
  }
  EXPECT_EQ(
      polygons_of_faces(a, a + Vec3(0.0f, 0.31f, 0.18f), a + Vec3(0.21f, 0.02f, -0.36f), faces),
      std::vector<int32_t>(20, 0));
}

TEST(RadiosityPly, ReadsBackWhatRadWritesAndRecoversPolygons) {
  const Hierarchy h = unit_square();
  const testing::MeshParts m = split_mesh(h);
  for (bool ascii : {false, true}) {
    const std::string path =
        std::string(RAD_BINARY_DIR) + (ascii ? "/compare_test_ascii.ply" : "/compare_test.ply");
    {
      std::ofstream out(path, std::ios::binary);
      write_ply(out, m.view(), ToneMap{}, ascii);
    }
    const PlyMesh back = read_radiosity_ply(path);
    ASSERT_EQ(back.position.size(), m.position.size());
    EXPECT_EQ(back.indices, m.indices);
    for (size_t v = 0; v < m.position.size(); ++v) {
      EXPECT_NEAR(glm::length(back.position[v] - m.position[v]), 0.0f, 1e-6f);
      EXPECT_NEAR(glm::length(back.radiosity[v] - m.radiosity[v]), 0.0f, 1e-5f);
    }
    EXPECT_EQ(assign_face_polygons(h.triangles, back.position, back.indices), m.face_polygon);
  }
}

}  // namespace
}  // namespace rad
