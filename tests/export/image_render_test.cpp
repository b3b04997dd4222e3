#include "export/image_render.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.h"
#include "export/output_mesh.h"
#include "mesh_parts.h"

namespace rad {
namespace {

// Objects of the test scene, for telling which one a reference sample hit.
enum Object : int { kNone = -1, kFloor = 0, kBlocker = 1, kWall = 2 };

struct TestScene {
  testing::MeshParts mesh;
  std::vector<int> face_object;
  Camera camera;
  RenderOptions options;
};

const Vec3 kShadow(0.03f, 0.03f, 0.03f);
const Vec3 kBlockerColour(0.9f, 0.2f, 0.1f);

/// Radiosity of the lit floor: varies with depth, so only perspective-correct interpolation
/// reproduces it.
Vec3 lit(float z) { return Vec3(0.2f, 0.4f, 0.6f) * (1.0f + 0.2f * z); }
bool in_shadow(float x, float z) { return x > 0.4f && x < 1.6f && z > -1.6f && z < -0.4f; }

void add_quad(TestScene& s, int object, std::array<Vec3, 4> p, std::array<Vec3, 4> c) {
  const uint32_t n = uint32_t(s.mesh.position.size());
  for (int k = 0; k < 4; ++k) {
    s.mesh.position.push_back(p[size_t(k)]);
    s.mesh.radiosity.push_back(c[size_t(k)]);
    s.mesh.display.push_back(c[size_t(k)]);
  }
  s.mesh.indices.insert(s.mesh.indices.end(), {n, n + 1, n + 2, n, n + 2, n + 3});
  s.mesh.face_polygon.insert(s.mesh.face_polygon.end(), {object, object});
  s.face_object.insert(s.face_object.end(), {object, object});
}

/// A floor 4 x 4 (y = 0, facing up) in 8 x 8 cells, lit except a 2 x 2-cell shadow; a blocker
/// quad floating above it, facing up; a wall facing away from the camera (so drawn black).
TestScene make_scene() {
  TestScene s;
  const int n = 8;
  std::vector<uint32_t> grid;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const float x = -2.0f + 0.5f * float(i), z = -2.0f + 0.5f * float(j);
      s.mesh.position.push_back(Vec3(x, 0.0f, z));
      const Vec3 b = in_shadow(x, z) ? kShadow : lit(z);
      s.mesh.radiosity.push_back(b);
      s.mesh.display.push_back(b);
    }
  }
  auto at = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      // (x0,z0) (x0,z1) (x1,z1) and (x0,z0) (x1,z1) (x1,z0): fronts face +y.
      s.mesh.indices.insert(s.mesh.indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j + 1),
                                                   at(i, j), at(i + 1, j + 1), at(i + 1, j)});
      s.mesh.face_polygon.insert(s.mesh.face_polygon.end(), {kFloor, kFloor});
      s.face_object.insert(s.face_object.end(), {kFloor, kFloor});
    }
  }
  const Vec3 k = kBlockerColour;
  add_quad(s, kBlocker,
           {Vec3(-1.5f, 0.5f, -0.5f), Vec3(-1.5f, 0.5f, 0.5f), Vec3(-0.5f, 0.5f, 0.5f),
            Vec3(-0.5f, 0.5f, -0.5f)},
           {k, k, k, k});
  const Vec3 w(5.0f);
  add_quad(s, kWall,
           {Vec3(0.5f, 0.0f, 1.5f), Vec3(1.5f, 0.0f, 1.5f), Vec3(1.5f, 0.8f, 1.5f),
            Vec3(0.5f, 0.8f, 1.5f)},
           {w, w, w, w});  // front faces +z, away from the eye
  s.camera.eye = Vec3(0.0f, 3.0f, -4.5f);
  s.camera.target = Vec3(0.0f, 0.0f, 0.5f);
  s.camera.fov_y_deg = 45.0f;
  s.options.width = 64;
  s.options.height = 48;
  s.options.samples = 4;
  return s;
}

Image render(const TestScene& s) {
  return render_image(s.mesh.position, s.mesh.display, s.mesh.indices, s.camera, s.options);
}

/// An independent reference: one ray per subsample, nearest hit, barycentric colour.
class Reference {
 public:
  explicit Reference(const TestScene& s) : s_(s) {
    const Camera& c = s.camera;
    fwd_ = glm::normalize(glm::dvec3(c.target - c.eye));
    right_ = glm::normalize(glm::cross(fwd_, glm::dvec3(0, 1, 0)));
    up_ = glm::cross(right_, fwd_);
    ty_ = std::tan(double(c.fov_y_deg) * M_PI / 360.0);
    tx_ = ty_ * s.options.width / s.options.height;
  }

  struct Hit {
    int object = kNone;
    Vec3 colour{0.0f};
    Vec3 point{0.0f};
  };

  /// What the ray through image position (u, v) in pixels sees.
  Hit trace(double u, double v) const {
    const glm::dvec3 d = fwd_ + (2.0 * u / s_.options.width - 1.0) * tx_ * right_ +
                         (1.0 - 2.0 * v / s_.options.height) * ty_ * up_;
    const glm::dvec3 o(s_.camera.eye);
    Hit best;
    double best_t = 1e300;
    const auto& m = s_.mesh;
    for (size_t f = 0; f < m.face_count(); ++f) {
      const uint32_t* i = &m.indices[3 * f];
      const glm::dvec3 a(m.position[i[0]]), b(m.position[i[1]]), c(m.position[i[2]]);
      const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
      const double det = glm::dot(e1, p);
      if (std::abs(det) < 1e-14) continue;
      const glm::dvec3 t0 = o - a;
      const double bu = glm::dot(t0, p) / det;
      const glm::dvec3 q = glm::cross(t0, e1);
      const double bv = glm::dot(d, q) / det, t = glm::dot(e2, q) / det;
      if (bu < 0 || bv < 0 || bu + bv > 1 || t <= 0 || t >= best_t) continue;
      best_t = t;
      const bool front = glm::dot(glm::cross(e1, e2), d) < 0;
      best.object = s_.face_object[f];
      best.point = Vec3(o + t * d);
      best.colour = front ? Vec3(float(1 - bu - bv) * m.display[i[0]] +
                                 float(bu) * m.display[i[1]] + float(bv) * m.display[i[2]])
                          : Vec3(0.0f);
    }
    return best;
  }

  /// Box-filtered pixel value; `uniform` tells whether every subsample, nudged either way by
  /// 1/100 of a pixel, hits the same object (so rounding at edges cannot change the pixel).
  Vec3 pixel(int x, int y, bool* uniform = nullptr, std::vector<Vec3>* points = nullptr) const {
    const int n = s_.options.samples;
    Vec3 sum(0.0f);
    int first = -2;
    bool same = true;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const double u = x + (i + 0.5) / n, v = y + (j + 0.5) / n;
        const Hit h = trace(u, v);
        sum += h.colour;
        if (points) points->push_back(h.point);
        for (double du : {-0.01, 0.0, 0.01}) {
          for (double dv : {-0.01, 0.0, 0.01}) {
            const int o = trace(u + du, v + dv).object;
            if (first == -2) first = o;
            same = same && o == first;
          }
        }
      }
    }
    if (uniform) *uniform = same;
    return sum / float(n * n);
  }

  /// The pixel holding world point p.
  std::array<int, 2> pixel_of(Vec3 p) const {
    const glm::dvec3 d = glm::dvec3(p) - glm::dvec3(s_.camera.eye);
    const double z = glm::dot(d, fwd_);
    const double u = (0.5 + 0.5 * glm::dot(d, right_) / (z * tx_)) * s_.options.width;
    const double v = (0.5 - 0.5 * glm::dot(d, up_) / (z * ty_)) * s_.options.height;
    return {int(std::floor(u)), int(std::floor(v))};
  }

 private:
  const TestScene& s_;
  glm::dvec3 fwd_, right_, up_;
  double tx_, ty_;
};

void expect_near(const Vec3& a, const Vec3& b, float tol, const std::string& what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], tol) << what << " channel " << k;
}

TEST(ImageRender, LitFloorPixelIsThePerspectiveCorrectGouraudValue) {
  const TestScene s = make_scene();
  const Image img = render(s);
  const Reference ref(s);
  const auto [x, y] = ref.pixel_of(Vec3(-1.0f, 0.0f, -1.25f));
  bool uniform = false;
  std::vector<Vec3> points;
  const Vec3 expected = ref.pixel(x, y, &uniform, &points);
  ASSERT_TRUE(uniform);
  // Computed from the mesh, not the reference's barycentrics: the floor's lit radiosity is
  // linear in z, so Gouraud interpolation reproduces it exactly at every subsample.
  Vec3 from_mesh(0.0f);
  for (const Vec3& p : points) from_mesh += lit(p.z) / float(points.size());
  expect_near(expected, from_mesh, 1e-5f, "reference vs mesh");
  expect_near(img.at(x, y), from_mesh, 1e-5f, "lit floor");
  // An affine (screen-space) interpolation would be off by more than this across the floor.
  const auto [x2, y2] = ref.pixel_of(Vec3(-1.0f, 0.0f, 1.75f));
  expect_near(img.at(x2, y2), ref.pixel(x2, y2), 1e-5f, "far lit floor");
}

TEST(ImageRender, ShadowedBlockerBackFaceAndBackgroundPixels) {
  const TestScene s = make_scene();
  const Image img = render(s);
  const Reference ref(s);
  struct Case {
    const char* name;
    Vec3 world;
    Vec3 expected;
  };
  const Case cases[] = {
      {"shadowed floor", Vec3(1.0f, 0.0f, -1.0f), kShadow},
      {"blocker", Vec3(-1.0f, 0.5f, 0.0f), kBlockerColour},
      {"wall seen from behind", Vec3(1.0f, 0.4f, 1.5f), Vec3(0.0f)},
  };
  for (const Case& c : cases) {
    const auto [x, y] = ref.pixel_of(c.world);
    bool uniform = false;
    const Vec3 r = ref.pixel(x, y, &uniform);
    ASSERT_TRUE(uniform) << c.name;
    expect_near(r, c.expected, 1e-6f, std::string(c.name) + " (reference)");
    expect_near(img.at(x, y), c.expected, 1e-6f, c.name);
  }
  // The top corners see past the floor's far edge.
  expect_near(img.at(0, 0), Vec3(0.0f), 0.0f, "background");
  expect_near(img.at(s.options.width - 1, 0), Vec3(0.0f), 0.0f, "background");
}

TEST(ImageRender, EveryPixelAwayFromEdgesMatchesTheReference) {
  const TestScene s = make_scene();
  const Image img = render(s);
  const Reference ref(s);
  int checked = 0, edge = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      bool uniform = false;
      const Vec3 r = ref.pixel(x, y, &uniform);
      if (!uniform) {
        ++edge;
        // Edge pixels may differ by the subsamples that lie within rounding of an edge.
        EXPECT_LE(max_component(glm::abs(img.at(x, y) - r)), 5.0f / 16.0f + 1e-4f) << x << "," << y;
        continue;
      }
      ++checked;
      expect_near(img.at(x, y), r, 1e-5f, "pixel " + std::to_string(x) + "," + std::to_string(y));
    }
  }
  EXPECT_GT(checked, 5 * edge);
}

TEST(ImageRender, SharedEdgesAreWatertight) {
  // A jittered 40 x 40 grid of triangles filling the view, seen at an angle: any crack or
  // double-counted subsample would show as a pixel other than exactly 1.
  testing::MeshParts m;
  const int n = 40;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> jitter(-0.4f, 0.4f);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const bool border = i == 0 || j == 0 || i == n || j == n;
      const float x = float(i) + (border ? 0.0f : jitter(rng));
      const float y = float(j) + (border ? 0.0f : jitter(rng));
      m.position.push_back(Vec3(x / n * 8.0f - 4.0f, y / n * 8.0f - 4.0f, 0.3f * x / n));
      m.display.push_back(Vec3(1.0f));
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      if ((i + j) % 2) {
        m.indices.insert(m.indices.end(), {a, c, d, a, d, b});
      } else {
        m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
      }
    }
  }
  Camera cam;
  cam.eye = Vec3(0.3f, -0.2f, -3.0f);
  cam.target = Vec3(0.0f, 0.0f, 0.0f);
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {  // the other winding, seen from the other side
      for (size_t f = 0; f < m.indices.size(); f += 3)
        std::swap(m.indices[f + 1], m.indices[f + 2]);
      cam.eye.z = 3.0f;
    }
    const Image img = render_image(m.position, m.display, m.indices, cam, {97, 61, 4});
    int bad = 0;
    for (const Vec3& p : img.pixels) bad += std::abs(p.x - 1.0f) > 1e-6f;
    EXPECT_EQ(bad, 0) << "pass " << pass;
  }
}

TEST(ImageRender, ClipsFacesThatReachBehindTheEye) {
  // A huge floor under an eye looking level: below the horizon every pixel is floor.
  testing::MeshParts m;
  const float r = 1e4f;
  m.position = {Vec3(-r, 0, -r), Vec3(-r, 0, r), Vec3(r, 0, r), Vec3(r, 0, -r)};
  m.display.assign(4, Vec3(0.5f));
  m.indices = {0, 1, 2, 0, 2, 3};
  Camera cam;
  cam.eye = Vec3(0.0f, 1.0f, 0.0f);
  cam.target = Vec3(0.0f, 1.0f, 1.0f);
  const Image img = render_image(m.position, m.display, m.indices, cam, {32, 32, 2});
  for (int x = 0; x < 32; ++x) {
    for (int y = 0; y < 15; ++y) EXPECT_EQ(img.at(x, y).x, 0.0f) << x << "," << y;
    for (int y = 17; y < 32; ++y) EXPECT_NEAR(img.at(x, y).x, 0.5f, 1e-6f) << x << "," << y;
  }
}

TEST(ImageRender, IsDeterministicAndChecksItsOptions) {
  const TestScene s = make_scene();
  EXPECT_EQ(render(s).pixels, render(s).pixels);
  RenderOptions bad = s.options;
  bad.width = 0;
  EXPECT_THROW(render_image(s.mesh.position, s.mesh.display, s.mesh.indices, s.camera, bad), Error);
  bad = s.options;
  bad.samples = 17;
  EXPECT_THROW(render_image(s.mesh.position, s.mesh.display, s.mesh.indices, s.camera, bad), Error);
}

}  // namespace
}  // namespace rad
