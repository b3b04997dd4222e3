#include "scenegen/scenegen.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <numbers>
#include <ostream>
#include <string>
#include <vector>

#include "core/error.h"

namespace rad {

namespace {

using Tris = std::vector<std::array<Vec3, 3>>;

// SplitMix64 (Steele, Lea, Flood 2014): tiny, and identical on every platform, unlike the
// standard distributions.
class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  float uniform() { return float(double(next() >> 11) * 0x1.0p-53); }
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
  Vec3 unit_vector() {
    float z = uniform(-1.0f, 1.0f), phi = uniform(0.0f, 6.2831853f);
    float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
  }

 private:
  uint64_t state_;
};

Material grey(float rho) { return {Vec3(rho), Vec3(0.0f)}; }
Material light(float e) { return {Vec3(0.0f), Vec3(e)}; }

// The quad p + [0,1]·u + [0,1]·v cut into nu × nv cells of two triangles each, front face
// towards `facing` (u × v or its opposite).
void add_quad(Tris& out, Vec3 p, Vec3 u, Vec3 v, int nu, int nv, Vec3 facing) {
  if (glm::dot(glm::cross(u, v), facing) < 0.0f) std::swap(u, v), std::swap(nu, nv);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      Vec3 a = p + u * (float(i) / nu) + v * (float(j) / nv);
      Vec3 b = p + u * (float(i + 1) / nu) + v * (float(j) / nv);
      Vec3 c = p + u * (float(i + 1) / nu) + v * (float(j + 1) / nv);
      Vec3 d = p + u * (float(i) / nu) + v * (float(j + 1) / nv);
      out.push_back({a, b, c});
      out.push_back({a, c, d});
    }
  }
}

// Axis-aligned box [lo, hi], each face n × n quads, facing outwards (or inwards).
void add_box(Tris& out, Vec3 lo, Vec3 hi, int n, bool inward = false) {
  Vec3 e = hi - lo;
  float s = inward ? -1.0f : 1.0f;
  Vec3 x(e.x, 0, 0), y(0, e.y, 0), z(0, 0, e.z);
  add_quad(out, lo, y, z, n, n, Vec3(-s, 0, 0));
  add_quad(out, lo + x, y, z, n, n, Vec3(s, 0, 0));
  add_quad(out, lo, x, z, n, n, Vec3(0, -s, 0));
  add_quad(out, lo + y, x, z, n, n, Vec3(0, s, 0));
  add_quad(out, lo, x, y, n, n, Vec3(0, 0, -s));
  add_quad(out, lo + z, x, y, n, n, Vec3(0, 0, s));
}

// UV sphere: stacks × slices quads (triangles at the poles collapse and are skipped).
void add_sphere(Tris& out, Vec3 centre, float r, int stacks, int slices) {
  auto point = [&](int i, int j) {
    float theta = 3.14159265f * float(i) / stacks, phi = 6.2831853f * float(j) / slices;
    return centre + r * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                             std::sin(theta) * std::sin(phi));
  };
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      Vec3 a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1), d = point(i, j + 1);
      // Outward: (b − a) × (c − a) points away from the centre for this winding.
      if (i + 1 < stacks) out.push_back({a, c, b});
      if (i > 0) out.push_back({a, d, c});
    }
  }
}

// A point of the quad p + u·[0,1] + v·[0,1] grid of stops su × sv, oriented like add_quad.
// Shapes below are grids of such points mapped onto a surface: `at(i, j)` gives grid point
// (i, j) of an nu × nv grid, and the cells are cut in two with the front towards `outward(i, j)`
// (a point that lies off the front side). Cells that map to slivers are skipped.
template <class At, class Out>
void add_grid(Tris& out, int nu, int nv, At at, Out outward) {
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      Vec3 a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      Vec3 o = outward(i, j);
      for (std::array<Vec3, 3> t : {std::array<Vec3, 3>{a, b, c}, std::array<Vec3, 3>{a, c, d}}) {
        Vec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
        float len = glm::length(n);
        float scale = glm::length(c - a) + glm::length(d - b);
        if (!(len > 1e-6f * scale * scale)) continue;
        if (glm::dot(n, o - (t[0] + t[1] + t[2]) / 3.0f) < 0.0f) std::swap(t[1], t[2]);
        out.push_back(t);
      }
    }
  }
}

// Stops along [lo, hi] for a rounded box of radius r: m in each rounded band, `flat` between.
std::vector<float> rounded_stops(float lo, float hi, float r, int m, int flat) {
  std::vector<float> s;
  for (int i = 0; i < m; ++i) s.push_back(lo + r * (1.0f - std::cos(1.5707963f * i / m)));
  for (int i = 0; i <= flat; ++i) s.push_back(lo + r + (hi - lo - 2 * r) * float(i) / flat);
  for (int i = m - 1; i >= 0; --i) s.push_back(hi - r * (1.0f - std::cos(1.5707963f * i / m)));
  return s;
}

// A box [lo, hi] with edges and corners rounded to radius r (a bevelled cushion): each face a
// grid whose points are pushed onto the box shrunk by r, plus r outwards. The flat middles are
// planar, the bands curved: what a modelled sofa is made of.
void add_rounded_box(Tris& out, Vec3 lo, Vec3 hi, float r, int m, int flat) {
  r = std::min(r, 0.49f * std::min({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}));
  const Vec3 inner_lo = lo + r, inner_hi = hi - r, centre = 0.5f * (lo + hi);
  auto round = [&](Vec3 p) {
    const Vec3 q = glm::clamp(p, inner_lo, inner_hi), d = p - q;
    const float len = glm::length(d);
    return len > 0.0f ? q + d * (r / len) : p;
  };
  const std::array<std::vector<float>, 3> stops = {rounded_stops(lo.x, hi.x, r, m, flat),
                                                   rounded_stops(lo.y, hi.y, r, m, flat),
                                                   rounded_stops(lo.z, hi.z, r, m, flat)};
  for (int axis = 0; axis < 3; ++axis) {
    const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
    const std::vector<float>&su = stops[ua], &sv = stops[va];
    for (float side : {lo[axis], hi[axis]}) {
      auto at = [&](int i, int j) {
        Vec3 p;
        p[axis] = side, p[ua] = su[i], p[va] = sv[j];
        return round(p);
      };
      auto outward = [&](int i, int j) {
        Vec3 p = at(i, j);
        return p + (p - centre);  // convex: every point lies in front of its own face
      };
      add_grid(out, int(su.size()) - 1, int(sv.size()) - 1, at, outward);
    }
  }
}

// A closed cylinder along y from `base`, `slices` around and `stacks` up, caps included.
void add_cylinder(Tris& out, Vec3 base, float radius, float height, int slices, int stacks) {
  auto ring = [&](int j, float y, float rr) {
    const float phi = 6.2831853f * float(j % slices) / slices;
    return base + Vec3(rr * std::cos(phi), y, rr * std::sin(phi));
  };
  const Vec3 axis_mid = base + Vec3(0, 0.5f * height, 0);
  add_grid(
      out, slices, stacks, [&](int j, int i) { return ring(j, height * i / stacks, radius); },
      [&](int j, int i) {
        Vec3 p = ring(j, height * i / stacks, radius);
        return p + 2.0f * (p - Vec3(axis_mid.x, p.y, axis_mid.z));
      });
  const int rings = std::max(1, stacks / 2);
  for (float y : {0.0f, height}) {
    add_grid(
        out, slices, rings,
        [&](int j, int i) { return ring(j, y, radius * float(i + 1) / (rings + 1)); },
        [&](int, int) { return base + Vec3(0, y == 0.0f ? -1.0f : height + 1.0f, 0); });
    for (int j = 0; j < slices; ++j) {  // the centre fan
      Vec3 c = base + Vec3(0, y, 0), a = ring(j, y, radius / (rings + 1)),
           b = ring(j + 1, y, radius / (rings + 1));
      std::array<Vec3, 3> t{c, a, b};
      if ((glm::cross(a - c, b - c).y > 0.0f) != (y > 0.0f)) std::swap(t[1], t[2]);
      out.push_back(t);
    }
  }
}

// A torus about the y axis through `centre`: ring radius big_r, tube radius small_r.
void add_torus(Tris& out, Vec3 centre, float big_r, float small_r, int nu, int nv) {
  auto tube_centre = [&](int i) {
    const float phi = 6.2831853f * float(i % nu) / nu;
    return centre + big_r * Vec3(std::cos(phi), 0.0f, std::sin(phi));
  };
  auto at = [&](int i, int j) {
    const float phi = 6.2831853f * float(i % nu) / nu, theta = 6.2831853f * float(j % nv) / nv;
    const Vec3 radial(std::cos(phi), 0.0f, std::sin(phi));
    return tube_centre(i) + small_r * (std::cos(theta) * radial + Vec3(0, std::sin(theta), 0));
  };
  add_grid(out, nu, nv, at, [&](int i, int j) {
    Vec3 p = at(i, j);
    return p + (p - tube_centre(i));
  });
}

// A leaf: a blade drooping from `base` along `dir` (unit, roughly horizontal), `length` long
// and up to `width` wide, with a top and an underside `thickness` apart (a leaf is seen from
// both sides; one-sided triangles back to back would be coincident).
void add_leaf(Tris& out, Vec3 base, Vec3 dir, float length, float width, float droop,
              float thickness, int n) {
  const Vec3 up(0, 1, 0);
  const Vec3 side = glm::normalize(glm::cross(dir, up));
  auto centre = [&](float s) {
    return base + dir * (length * s) + up * (length * (0.6f * s - droop * s * s));
  };
  auto normal = [&](float s) {
    const Vec3 tangent = dir * length + up * (length * (0.6f - 2.0f * droop * s));
    return glm::normalize(glm::cross(side, tangent));
  };
  auto surface = [&](int i, int j, float offset) {
    const float s = float(i) / n,
                w = (float(j) - 1.0f) * width * (0.15f + 0.85f * std::sin(3.14159265f * s));
    return centre(s) + side * (0.5f * w) + normal(s) * offset;
  };
  for (float face : {1.0f, -1.0f}) {
    const float offset = face > 0.0f ? 0.5f * thickness : -0.5f * thickness;
    add_grid(
        out, n, 2, [&](int i, int j) { return surface(i, j, offset); },
        [&](int i, int j) { return surface(i, j, offset) + face * normal(float(i) / n); });
  }
}

class Builder {
 public:
  explicit Builder(std::string name) { scene_.name = std::move(name); }
  int32_t pure(std::string name, Material m, Tris tris) {
    ObjectDescription o;
    o.name = std::move(name);
    o.kind = ObjectKind::Pure;
    o.material = m;
    o.triangles = std::move(tris);
    scene_.objects.push_back(std::move(o));
    return int32_t(scene_.objects.size()) - 1;
  }
  int32_t light(std::string name, Light l) {
    ObjectDescription o;
    o.name = l.name = std::move(name);
    o.light = std::move(l);
    scene_.objects.push_back(std::move(o));
    return int32_t(scene_.objects.size()) - 1;
  }
  int32_t group(ObjectKind kind, std::string name, std::vector<int32_t> children) {
    ObjectDescription o;
    o.name = std::move(name);
    o.kind = kind;
    o.children = std::move(children);
    scene_.objects.push_back(std::move(o));
    return int32_t(scene_.objects.size()) - 1;
  }
  void root(int32_t id) { scene_.roots.push_back(id); }
  ObjectDescription& object(int32_t id) { return scene_.objects[size_t(id)]; }
  SceneDescription take() { return std::move(scene_); }

 private:
  SceneDescription scene_;
};

Tris box_tris(Vec3 lo, Vec3 hi, int n) {
  Tris t;
  add_box(t, lo, hi, n);
  return t;
}

// A table (top + 4 legs) or a chair (seat, back, 4 legs) at (x, z) on the floor y = floor_y.
int32_t furniture(Builder& b, bool table, Vec3 at, float scale, int tess, int serial) {
  std::vector<int32_t> parts;
  float w = (table ? 1.2f : 0.45f) * scale, h = (table ? 0.75f : 0.45f) * scale;
  float leg = 0.05f * scale, top = 0.04f * scale;
  Material wood = grey(0.5f);
  std::string base = fmt::format("{}{}", table ? "table" : "chair", serial);
  parts.push_back(
      b.pure(base + ".top", wood, box_tris(at + Vec3(0, h - top, 0), at + Vec3(w, h, w), tess)));
  for (int k = 0; k < 4; ++k) {
    Vec3 o = at + Vec3((k & 1) ? w - leg : 0.0f, 0.0f, (k & 2) ? w - leg : 0.0f);
    parts.push_back(b.pure(fmt::format("{}.leg{}", base, k), wood,
                           box_tris(o, o + Vec3(leg, h - top, leg), tess)));
  }
  if (!table) {
    parts.push_back(
        b.pure(base + ".back", wood, box_tris(at + Vec3(0, h, 0), at + Vec3(w, 2 * h, top), tess)));
  }
  return b.group(ObjectKind::Composite, base, std::move(parts));
}

}  // namespace

const char* to_string(SceneKind kind) {
  switch (kind) {
    case SceneKind::CornellBox:
      return "cornell";
    case SceneKind::Soup:
      return "soup";
    case SceneKind::Nested:
      return "nested";
    case SceneKind::TeapotInStadium:
      return "stadium";
    case SceneKind::Building:
      return "building";
    case SceneKind::FurnishedRoom:
      return "room";
  }
  return "?";
}

SceneKind parse_scene_kind(std::string_view name) {
  for (SceneKind k : {SceneKind::CornellBox, SceneKind::Soup, SceneKind::Nested,
                      SceneKind::TeapotInStadium, SceneKind::Building, SceneKind::FurnishedRoom}) {
    if (name == to_string(k)) return k;
  }
  throw Error(fmt::format(
      "unknown scene kind \"{}\" (expected cornell, soup, nested, stadium, building or room)",
      name));
}

SceneDescription make_cornell_box(int k) {
  k = std::max(k, 1);
  Builder b("Cornell box");
  auto wall = [&](const char* name, Material m, Vec3 p, Vec3 u, Vec3 v, Vec3 facing) {
    Tris t;
    add_quad(t, p, u, v, k, k, facing);
    b.root(b.pure(name, m, std::move(t)));
  };
  Vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
  wall("floor", grey(0.75f), Vec3(0), X, Z, Y);
  wall("ceiling", grey(0.75f), Y, X, Z, -Y);
  wall("back", grey(0.75f), Vec3(0), X, Y, Z);
  wall("left", {Vec3(0.63f, 0.06f, 0.05f), Vec3(0.0f)}, Vec3(0), Y, Z, X);
  wall("right", {Vec3(0.14f, 0.45f, 0.09f), Vec3(0.0f)}, X, Y, Z, -X);
  Tris lamp;
  int kl = std::max(1, k / 8);
  add_quad(lamp, Vec3(0.4f, 0.999f, 0.4f), Vec3(0.2f, 0, 0), Vec3(0, 0, 0.2f), kl, kl, -Y);
  b.root(b.pure("light", light(10.0f), std::move(lamp)));
  int kb = std::max(1, k / 4);
  b.root(b.pure("short block", grey(0.75f),
                box_tris(Vec3(0.55f, 0.0f, 0.45f), Vec3(0.85f, 0.3f, 0.75f), kb)));
  b.root(b.pure("tall block", grey(0.75f),
                box_tris(Vec3(0.15f, 0.0f, 0.15f), Vec3(0.45f, 0.6f, 0.45f), kb)));
  return b.take();
}

SceneDescription make_triangle_soup(uint64_t n, uint64_t seed) {
  Rng rng(seed);
  Builder b("triangle soup");
  Tris t;
  t.reserve(n);
  float edge = 2.0f / std::cbrt(float(std::max<uint64_t>(n, 1)));
  while (t.size() < n) {
    Vec3 c(rng.uniform(), rng.uniform(), rng.uniform());
    Vec3 a = c + 0.5f * edge * rng.unit_vector();
    Vec3 p = c + 0.5f * edge * rng.unit_vector();
    Vec3 q = c + 0.5f * edge * rng.unit_vector();
    if (glm::length(glm::cross(p - a, q - a)) < 1e-3f * edge * edge) continue;
    t.push_back({a, p, q});
  }
  b.root(b.pure("soup", grey(0.5f), std::move(t)));
  return b.take();
}

SceneDescription make_nested_scene(int blocks, int per_block, int tess, uint64_t seed) {
  Rng rng(seed);
  Builder b("nested assemblies");
  const float field = 10.0f * std::sqrt(float(std::max(blocks, 1)));
  Tris ground;
  add_quad(ground, Vec3(0), Vec3(field, 0, 0), Vec3(0, 0, field), 8, 8, Vec3(0, 1, 0));
  b.root(b.pure("ground", grey(0.6f), std::move(ground)));
  int serial = 0;
  std::vector<int32_t> city;
  for (int i = 0; i < blocks; ++i) {
    Vec3 corner(rng.uniform(0.0f, field - 8.0f), 0.0f, rng.uniform(0.0f, field - 8.0f));
    // Two levels: a block holds rows, a row holds furniture Composites.
    std::vector<int32_t> rows;
    for (int r = 0; r < 2; ++r) {
      std::vector<int32_t> items;
      for (int j = r; j < per_block; j += 2) {
        Vec3 at = corner + Vec3(rng.uniform(0.0f, 7.0f), 0.0f, 3.5f * r + rng.uniform(0.0f, 3.0f));
        items.push_back(furniture(b, (j % 3) == 0, at, 1.0f, tess, serial++));
      }
      if (!items.empty()) {
        rows.push_back(b.group(ObjectKind::Assembly, fmt::format("block{}.row{}", i, r), items));
      }
    }
    Tris lamp;
    add_quad(lamp, corner + Vec3(3.5f, 3.0f, 3.5f), Vec3(1, 0, 0), Vec3(0, 0, 1), 1, 1,
             Vec3(0, -1, 0));
    rows.push_back(b.pure(fmt::format("block{}.light", i), light(5.0f), std::move(lamp)));
    city.push_back(b.group(ObjectKind::Assembly, fmt::format("block{}", i), rows));
  }
  b.root(b.group(ObjectKind::Assembly, "city", std::move(city)));
  return b.take();
}

SceneDescription make_teapot_in_stadium(int stacks) {
  stacks = std::max(stacks, 3);
  Builder b("teapot in a stadium");
  Tris room;
  add_box(room, Vec3(-50, 0, -50), Vec3(50, 30, 50), 8, /*inward=*/true);
  b.root(b.pure("stadium", grey(0.6f), std::move(room)));
  Tris lamp;
  add_quad(lamp, Vec3(-5, 29.9f, -5), Vec3(10, 0, 0), Vec3(0, 0, 10), 2, 2, Vec3(0, -1, 0));
  b.root(b.pure("light", light(20.0f), std::move(lamp)));
  Tris ball;
  add_sphere(ball, Vec3(0, 1, 0), 0.5f, stacks, 2 * stacks);
  b.root(b.pure("teapot", grey(0.8f), std::move(ball)));
  return b.take();
}

SceneDescription make_building(int nx, int nz, int wall_tess, int furniture_tess, uint64_t seed,
                               int lights_reach, const RoomLighting& lighting, int light_groups) {
  nx = std::max(nx, 1), nz = std::max(nz, 1);
  const int t = std::max(wall_tess, 1), f = std::max(furniture_tess, 1);
  Rng rng(seed);
  Builder b("building");
  const float w = 5.0f, h = 3.0f, door = 1.0f, door_h = 2.1f;
  const Vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
  int serial = 0;
  // building → one Assembly per row of rooms → rooms: Assemblies group what is near (design §3),
  // so a ray tests about nx + nz boxes, not nx · nz.
  std::vector<int32_t> rows;
  for (int i = 0; i < nx; ++i) {
    std::vector<int32_t> row;
    for (int k = 0; k < nz; ++k) {
      Vec3 o(w * i, 0.0f, w * k);
      Tris shell;
      add_quad(shell, o, w * X, w * Z, t, t, Y);
      add_quad(shell, o + h * Y, w * X, w * Z, t, t, -Y);
      // Walls at x = 0 and z = 0 of each room (interior sides both ways) with a centred door
      // when a neighbour lies beyond; outer walls at the far sides of the building.
      auto wall = [&](Vec3 p, Vec3 along, Vec3 facing, bool has_door) {
        if (!has_door) {
          add_quad(shell, p, w * along, h * Y, t, t, facing);
          return;
        }
        float side = 0.5f * (w - door);
        add_quad(shell, p, side * along, h * Y, t, t, facing);
        add_quad(shell, p + (side + door) * along, side * along, h * Y, t, t, facing);
        add_quad(shell, p + side * along + door_h * Y, door * along, (h - door_h) * Y, t, 1,
                 facing);
      };
      wall(o, Z, X, i > 0);
      wall(o, X, Z, k > 0);
      wall(o + w * X, Z, -X, i + 1 < nx);
      wall(o + w * Z, X, -Z, k + 1 < nz);
      std::vector<int32_t> room;
      std::string name = fmt::format("room{}_{}", i, k);
      room.push_back(b.pure(name + ".shell", grey(0.7f), std::move(shell)));
      if (lighting.kind == RoomLighting::Kind::Point) {
        Light l;
        l.kind = LightKind::Point;
        l.position = o + Vec3(2.5f, h - 0.3f, 2.5f);
        l.intensity = 8.0f / std::numbers::pi_v<float>;
        room.push_back(b.light(name + ".light", l));
      } else if (lighting.kind == RoomLighting::Kind::Downlight) {
        assert(lighting.downlight);
        Light l;
        l.kind = LightKind::Point;
        l.position = o + Vec3(2.5f, h - 0.01f, 2.5f);
        l.direction = -Y;
        l.photometric_up = X;
        l.intensity = 1.0f;
        l.photometry = lighting.downlight;
        room.push_back(b.light(name + ".light", l));
      } else {
        Tris lamp;
        add_quad(lamp, o + Vec3(2.0f, h - 0.01f, 2.0f), X, Z, 1, 1, -Y);
        room.push_back(b.pure(name + ".light", light(8.0f), std::move(lamp)));
      }
      Vec3 table_at = o + Vec3(rng.uniform(1.0f, 2.8f), 0.0f, rng.uniform(1.0f, 2.8f));
      room.push_back(furniture(b, true, table_at, 1.0f, f, serial++));
      for (int c = 0; c < 3; ++c) {
        Vec3 at = table_at + Vec3(c == 0 ? -0.6f : 0.4f * c, 0.0f, c == 0 ? 0.4f : -0.6f);
        room.push_back(furniture(b, false, at, 1.0f, f, serial++));
      }
      Vec3 cab = o + Vec3(w - 0.7f, 0.0f, rng.uniform(1.5f, 3.0f));
      room.push_back(b.pure(name + ".cabinet", grey(0.4f),
                            box_tris(cab, cab + Vec3(0.6f, 1.8f, 0.8f), 2 * f)));
      const int32_t id = b.group(ObjectKind::Assembly, name, std::move(room));
      if (light_groups > 0)  // rooms dealt round the groups like cards
        b.object(id).flags.group = fmt::format("g{}", (i * nz + k) % light_groups);
      if (lights_reach >= 0) {  // it lights itself and the rooms within reach
        ObjectFlags& flags = b.object(id).flags;
        flags.has_lights = true;
        for (int di = -lights_reach; di <= lights_reach; ++di) {
          for (int dk = -lights_reach; dk <= lights_reach; ++dk) {
            const int a = i + di, c = k + dk;
            if ((di || dk) && a >= 0 && a < nx && c >= 0 && c < nz) {
              flags.lights.push_back({fmt::format("room{}_{}", a, c), {}});
            }
          }
        }
      }
      row.push_back(id);
    }
    rows.push_back(b.group(ObjectKind::Assembly, fmt::format("row{}", i), std::move(row)));
  }
  b.root(b.group(ObjectKind::Assembly, "building", std::move(rows)));
  return b.take();
}

SceneDescription make_furnished_room(int q, uint64_t seed) {
  q = std::max(q, 1);
  Rng rng(seed);
  Builder b("furnished room");
  const float w = 5.0f, h = 2.8f, d = 4.0f;
  const Vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
  const int t = 2 * q;
  std::vector<int32_t> room;
  auto pure = [&](std::string name, Material m, Tris tris) {
    room.push_back(b.pure(std::move(name), m, std::move(tris)));
  };
  auto color = [](float r, float g, float bl) { return Material{Vec3(r, g, bl), Vec3(0.0f)}; };
  {
    Tris floor, ceiling, walls;
    add_quad(floor, Vec3(0), w * X, d * Z, t, t, Y);
    add_quad(ceiling, h * Y, w * X, d * Z, t, t, -Y);
    add_quad(walls, Vec3(0), w * X, h * Y, t, t, Z);
    add_quad(walls, d * Z, w * X, h * Y, t, t, -Z);
    add_quad(walls, Vec3(0), d * Z, h * Y, t, t, X);
    add_quad(walls, w * X, d * Z, h * Y, t, t, -X);
    pure("floor", color(0.55f, 0.4f, 0.25f), std::move(floor));
    pure("ceiling", grey(0.8f), std::move(ceiling));
    pure("walls", color(0.75f, 0.72f, 0.65f), std::move(walls));
  }
  Tris panel;
  add_quad(panel, Vec3(2.0f, h - 0.01f, 1.5f), X, Z, 1, 1, -Y);
  pure("ceiling light", light(10.0f), std::move(panel));

  std::vector<int32_t> parts;
  auto part = [&](std::string name, Material m, Tris tris) {
    parts.push_back(b.pure(std::move(name), m, std::move(tris)));
  };
  auto group = [&](std::string name) {
    room.push_back(b.group(ObjectKind::Composite, std::move(name), std::move(parts)));
    parts.clear();
  };
  auto rounded = [&](Vec3 lo, Vec3 hi, float r) {
    Tris out;
    add_rounded_box(out, lo, hi, r, std::max(2, q), std::max(1, q / 2));
    return out;
  };
  // A sofa against the back wall and an armchair facing it: cushions with rounded edges.
  const Material fabric = color(0.6f, 0.18f, 0.14f), leather = color(0.35f, 0.22f, 0.12f);
  part("sofa.seat", fabric, rounded(Vec3(1.3f, 0.1f, 0.1f), Vec3(3.3f, 0.45f, 0.95f), 0.08f));
  part("sofa.back", fabric, rounded(Vec3(1.3f, 0.1f, 0.05f), Vec3(3.3f, 0.9f, 0.3f), 0.08f));
  part("sofa.left arm", fabric, rounded(Vec3(1.05f, 0.1f, 0.05f), Vec3(1.3f, 0.65f, 0.95f), 0.08f));
  part("sofa.right arm", fabric,
       rounded(Vec3(3.3f, 0.1f, 0.05f), Vec3(3.55f, 0.65f, 0.95f), 0.08f));
  for (int k = 0; k < 4; ++k) {
    Tris leg;
    add_cylinder(leg, Vec3((k & 1) ? 3.45f : 1.15f, 0.0f, (k & 2) ? 0.85f : 0.15f), 0.03f, 0.1f,
                 4 + 2 * q, 1);
    part(fmt::format("sofa.leg{}", k), leather, std::move(leg));
  }
  group("sofa");
  part("armchair.seat", leather, rounded(Vec3(3.7f, 0.0f, 2.6f), Vec3(4.6f, 0.42f, 3.5f), 0.1f));
  part("armchair.back", leather, rounded(Vec3(3.7f, 0.0f, 3.3f), Vec3(4.6f, 0.95f, 3.6f), 0.1f));
  part("armchair.left arm", leather,
       rounded(Vec3(3.55f, 0.0f, 2.6f), Vec3(3.75f, 0.62f, 3.6f), 0.08f));
  part("armchair.right arm", leather,
       rounded(Vec3(4.55f, 0.0f, 2.6f), Vec3(4.75f, 0.62f, 3.6f), 0.08f));
  group("armchair");
  // A coffee table on four legs with a ring, a bowl of fruit and a vase on it.
  const Material wood = color(0.5f, 0.32f, 0.18f);
  part("table.top", wood, rounded(Vec3(1.7f, 0.40f, 1.6f), Vec3(2.9f, 0.45f, 2.3f), 0.02f));
  for (int k = 0; k < 4; ++k) {
    Tris leg;
    add_cylinder(leg, Vec3((k & 1) ? 2.8f : 1.8f, 0.0f, (k & 2) ? 2.2f : 1.7f), 0.025f, 0.4f,
                 4 + 2 * q, 2);
    part(fmt::format("table.leg{}", k), wood, std::move(leg));
  }
  {
    Tris ring, fruit, vase;
    add_torus(ring, Vec3(2.0f, 0.47f, 1.8f), 0.1f, 0.02f, 8 * q, 3 * q);
    for (int k = 0; k < 5; ++k) {
      add_sphere(fruit, Vec3(2.35f + 0.09f * (k % 3), 0.5f, 1.9f + 0.1f * (k / 3)), 0.045f, 3 * q,
                 6 * q);
    }
    add_cylinder(vase, Vec3(2.6f, 0.45f, 2.1f), 0.06f, 0.25f, 6 * q, 2 * q);
    part("table.ring", color(0.8f, 0.7f, 0.3f), std::move(ring));
    part("table.fruit", color(0.8f, 0.45f, 0.1f), std::move(fruit));
    part("table.vase", color(0.2f, 0.3f, 0.6f), std::move(vase));
  }
  group("coffee table");
  // A bookshelf on the left wall: a frame, shelves and books of random colours.
  {
    const float x0 = 0.02f, z0 = 1.2f, depth = 0.35f, wide = 1.6f, tall = 2.0f;
    Tris frame;
    add_box(frame, Vec3(x0, 0, z0), Vec3(x0 + depth, tall, z0 + 0.03f), q);
    add_box(frame, Vec3(x0, 0, z0 + wide - 0.03f), Vec3(x0 + depth, tall, z0 + wide), q);
    for (int k = 0; k < 5; ++k) {
      const float y = 0.05f + 0.48f * k;
      add_box(frame, Vec3(x0, y, z0 + 0.03f), Vec3(x0 + depth, y + 0.03f, z0 + wide - 0.03f), q);
    }
    part("shelf.frame", wood, std::move(frame));
    for (int k = 0; k < 4; ++k) {
      Tris books;
      float z = z0 + 0.05f;
      const float y = 0.08f + 0.48f * k;
      while (z < z0 + wide - 0.1f) {
        const float thick = rng.uniform(0.02f, 0.06f), high = rng.uniform(0.22f, 0.4f);
        add_box(books, Vec3(x0 + 0.03f, y, z),
                Vec3(x0 + rng.uniform(0.22f, 0.3f), y + high, z + thick), 1);
        z += thick + 0.002f;
      }
      part(fmt::format("shelf.books{}", k),
           color(rng.uniform(0.2f, 0.7f), rng.uniform(0.1f, 0.5f), rng.uniform(0.1f, 0.5f)),
           std::move(books));
    }
    group("bookshelf");
  }
  // A plant in the corner: a pot and thin two-sided leaves in every direction.
  {
    const Vec3 pot_at(4.5f, 0.0f, 0.5f);
    Tris pot, leaves;
    add_cylinder(pot, pot_at, 0.18f, 0.35f, 8 * q, 2 * q);
    const int n_leaves = 40 + 10 * q;
    for (int k = 0; k < n_leaves; ++k) {
      const float yaw = rng.uniform(0.0f, 6.2831853f), pitch = rng.uniform(-0.2f, 0.9f);
      const Vec3 dir = glm::normalize(Vec3(std::cos(yaw), 0.0f, std::sin(yaw)) * std::cos(pitch) +
                                      Vec3(0, std::sin(pitch), 0) * 0.5f);
      const Vec3 base = pot_at + Vec3(0.0f, 0.35f + rng.uniform(0.0f, 0.6f), 0.0f) +
                        0.03f * Vec3(std::cos(yaw), 0.0f, std::sin(yaw));
      add_leaf(leaves, base, dir, rng.uniform(0.25f, 0.45f), rng.uniform(0.04f, 0.08f),
               rng.uniform(0.8f, 1.6f), 0.002f, 2 + 2 * q);
    }
    part("plant.pot", color(0.6f, 0.3f, 0.2f), std::move(pot));
    part("plant.leaves", color(0.15f, 0.45f, 0.12f), std::move(leaves));
    group("plant");
  }
  // A floor lamp by the sofa: a pole and a glowing globe (a curved emitter), and a ball.
  {
    Tris pole, globe, ball;
    add_cylinder(pole, Vec3(0.7f, 0.0f, 0.4f), 0.02f, 1.45f, 4 + 2 * q, 4);
    add_sphere(globe, Vec3(0.7f, 1.6f, 0.4f), 0.15f, 4 * q, 8 * q);
    add_sphere(ball, Vec3(3.2f, 0.15f, 3.2f), 0.15f, 4 * q, 8 * q);
    part("lamp.pole", grey(0.3f), std::move(pole));
    part("lamp.globe", light(6.0f), std::move(globe));
    group("floor lamp");
    pure("ball", color(0.2f, 0.5f, 0.7f), std::move(ball));
  }
  b.root(b.group(ObjectKind::Assembly, "room", std::move(room)));
  return b.take();
}

std::string downlight_ies() {
  std::string gammas, candela;
  for (int g = 0; g <= 90; ++g) {
    gammas += fmt::format("{}{}", g ? " " : "", g);
    const double c = 8.0 / std::numbers::pi * std::cos(double(g) * std::numbers::pi / 180.0);
    candela += fmt::format("{}{:.6f}", g ? " " : "", g == 90 ? 0.0 : c);
  }
  return "IESNA:LM-63-2002\n"
         "[TEST] rad-gen building --downlights\n"
         "[LUMINAIRE] the far field of a 1 m2 Lambertian panel of exitance 8: (8/pi) cos(gamma) "
         "cd\n"
         "TILT=NONE\n"
         "1 -1 1 91 1 1 2 0 0 0\n"
         "1 1 0\n" +
         gammas + "\n0\n" + candela + "\n";
}

SceneDescription generate_scene(SceneKind kind, uint64_t triangles, uint64_t seed, int lights_reach,
                                const RoomLighting& lighting, int light_groups) {
  double n = double(std::max<uint64_t>(triangles, 1));
  switch (kind) {
    case SceneKind::CornellBox:
      return make_cornell_box(int(std::lround(std::sqrt(n / 11.5))));
    case SceneKind::Soup:
      return make_triangle_soup(triangles, seed);
    case SceneKind::Nested: {
      // Tables 5 boxes, chairs 6: ~5.7 boxes × 12 tess² triangles per Composite, tess 2.
      int composites = std::max(1, int(n / (5.7 * 12 * 4)));
      int blocks = std::max(1, int(std::sqrt(composites / 2.0)));
      return make_nested_scene(blocks, std::max(1, composites / blocks), 2, seed);
    }
    case SceneKind::TeapotInStadium:
      return make_teapot_in_stadium(int(std::lround(std::sqrt(n / 4.0))));
    case SceneKind::Building: {
      int rooms = std::max(1, int(std::lround(n / 1600.0)));
      int nx = std::max(1, int(std::lround(std::sqrt(double(rooms)))));
      return make_building(nx, std::max(1, (rooms + nx - 1) / nx), 4, 2, seed, lights_reach,
                           lighting, light_groups);
    }
    case SceneKind::FurnishedRoom: {
      // The triangle count grows about as q^2: counted at q = 4, then scaled.
      size_t at4 = 0;
      for (const auto& o : make_furnished_room(4, seed).objects) at4 += o.triangles.size();
      const int q = int(std::lround(4.0 * std::sqrt(n / double(at4))));
      return make_furnished_room(std::clamp(q, 1, 256), seed);
    }
  }
  throw Error("unknown scene kind");
}

std::vector<std::array<Vec3, 3>> tessellate_triangles(const std::vector<std::array<Vec3, 3>>& in,
                                                      int k) {
  std::vector<std::array<Vec3, 3>> out;
  out.reserve(in.size() * size_t(k) * size_t(k));
  for (const auto& t : in) {
    // Grid point (i, j): a + i/k (b - a) + j/k (c - a), i + j <= k.
    auto at = [&](int i, int j) {
      const float u = float(i) / float(k), v = float(j) / float(k);
      return t[0] * (1.0f - u - v) + t[1] * u + t[2] * v;
    };
    for (int j = 0; j < k; ++j) {
      for (int i = 0; i + j < k; ++i) {
        out.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 1 < k) out.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  }
  return out;
}

}  // namespace rad
