#include "scenegen/scenegen.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
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
  }
  return "?";
}

SceneKind parse_scene_kind(std::string_view name) {
  for (SceneKind k : {SceneKind::CornellBox, SceneKind::Soup, SceneKind::Nested,
                      SceneKind::TeapotInStadium, SceneKind::Building}) {
    if (name == to_string(k)) return k;
  }
  throw Error(fmt::format(
      "unknown scene kind \"{}\" (expected cornell, soup, nested, stadium or building)", name));
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
                               int lights_reach) {
  nx = std::max(nx, 1), nz = std::max(nz, 1);
  const int t = std::max(wall_tess, 1), f = std::max(furniture_tess, 1);
  Rng rng(seed);
  Builder b("building");
  const float w = 5.0f, h = 3.0f, door = 1.0f, door_h = 2.1f;
  const Vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
  int serial = 0;
  // building → one Assembly per row of rooms → rooms: Assemblies group what is near (SPEC §3),
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
      Tris lamp;
      add_quad(lamp, o + Vec3(2.0f, h - 0.01f, 2.0f), X, Z, 1, 1, -Y);
      room.push_back(b.pure(name + ".light", light(8.0f), std::move(lamp)));
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
      if (lights_reach >= 0) {  // it lights itself and the rooms within reach
        ObjectFlags& f = b.object(id).flags;
        f.has_lights = true;
        for (int di = -lights_reach; di <= lights_reach; ++di) {
          for (int dk = -lights_reach; dk <= lights_reach; ++dk) {
            const int a = i + di, c = k + dk;
            if ((di || dk) && a >= 0 && a < nx && c >= 0 && c < nz) {
              f.lights.push_back({fmt::format("room{}_{}", a, c), {}});
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

SceneDescription generate_scene(SceneKind kind, uint64_t triangles, uint64_t seed,
                                int lights_reach) {
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
      return make_building(nx, std::max(1, (rooms + nx - 1) / nx), 4, 2, seed, lights_reach);
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

void write_description(const SceneDescription& scene, std::ostream& out) {
  auto vec = [](const Vec3& v) { return fmt::format("<{:.9g} {:.9g} {:.9g}>", v.x, v.y, v.z); };
  auto write = [&](auto&& self, int32_t id, int depth) -> void {
    const ObjectDescription& o = scene.objects[id];
    std::string pad(2 * depth, ' ');
    out << pad << "Object \"" << o.name << "\" ";
    if (o.copy_of >= 0) {  // the latest complete object of that name, as when it was parsed
      out << "Copy \"" << scene.objects[size_t(o.copy_of)].name << '"';
    } else {
      out << to_string(o.kind);
    }
    for (const Transform& t : o.transforms) {
      const auto v = [](const DVec3& d) {
        return fmt::format("<{:.17g} {:.17g} {:.17g}>", d.x, d.y, d.z);
      };
      switch (t.kind) {
        case Transform::Kind::Translate: out << " Translate " << v(t.v); break;
        case Transform::Kind::Rotate: out << " Rotate " << v(t.v) << fmt::format(" {:.17g}", t.degrees); break;
        case Transform::Kind::Scale: out << " Scale " << v(t.v); break;
      }
    }
    const ObjectFlags& f = o.flags;
    if (f.casts_shadows) out << " CastsShadows " << (*f.casts_shadows ? "Yes" : "No");
    if (f.receives_shadows) out << " ReceivesShadows " << (*f.receives_shadows ? "Yes" : "No");
    if (f.has_lights) {
      out << " Lights {";
      for (const NamedObject& n : f.lights) out << " \"" << n.name << '"';
      out << " }";
    }
    if (o.copy_of >= 0) {
      out << "\n";
      return;
    }
    out << " {\n";
    if (o.kind == ObjectKind::Pure) {
      const Material& m = o.material;
      float rho = max_component(m.reflectance), e = max_component(m.emission);
      // One colour for both: reflectance if any, else the emission's.
      Vec3 color = rho > 0.0f ? m.reflectance / rho : (e > 0.0f ? m.emission / e : Vec3(1.0f));
      float emission = e > 0.0f ? mean_component(m.emission) / mean_component(color) : 0.0f;
      out << pad << "  Reflectivity " << fmt::format("{:.9g}", rho) << " Color " << vec(color)
          << " Emission " << fmt::format("{:.9g}", emission) << "\n";
      out << pad << "  Data {\n";
      for (const auto& t : o.triangles) {
        out << pad << "    " << vec(t[0]) << ' ' << vec(t[1]) << ' ' << vec(t[2]) << '\n';
      }
      out << pad << "  }\n";
    } else {
      for (int32_t c : o.children) self(self, c, depth + 1);
    }
    out << pad << "}\n";
  };
  out << '"' << scene.name << "\"\n";
  for (int32_t r : scene.roots) write(write, r, 0);
}

}  // namespace rad
