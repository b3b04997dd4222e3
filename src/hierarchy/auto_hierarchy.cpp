#include "hierarchy/auto_hierarchy.h"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "scene/model.h"
#include "scene/scene_file.h"

namespace rad {

namespace {

constexpr size_t kMaxCompositeParts = 32;
constexpr double kMinFill = 0.25;
constexpr double kMaxShare = 0.5;
constexpr double kMaxDensity = 4.0;

// A box's volume with every side at least `floor` long: flat parts (a wall, a table top) have
// no volume, yet they fill their group's box as much as a thin slab does.
double volume(const Aabb& b, float floor) {
  const Vec3 e = glm::max(b.extent(), Vec3(floor));
  return double(e.x) * double(e.y) * double(e.z);
}

struct Regrouper {
  const Hierarchy& h;
  SceneDescription out;
  // Without triangles, each Pure of `out` only names the Pure of h it is (`source`): what
  // placing the regrouped tree straight from h (Placer) needs.
  bool with_triangles = true;
  std::vector<int32_t> source;  // per object of `out`: the Pure of h, or -1

  // `mode` names the option in the error: a Lights list names objects that regrouping drops.
  Regrouper(const Hierarchy& hierarchy, const char* mode) : h(hierarchy) {
    for (const SceneObject& o : h.objects) {
      if (o.influence >= 0) {
        throw Error(o.loc, fmt::format("--hierarchy {} regroups the objects, so it cannot keep "
                                       "the Lights list of \"{}\" (use --hierarchy file)",
                                       mode, h.objects[size_t(o.influence)].name));
      }
    }
    out.name = h.scene_name;
    out.path = h.source_path;
    out.model = h.model;
  }

  // Pure `i` of h as a Pure of the output, its resolved flags written on it.
  int32_t pure(int32_t i) {
    const SceneObject& o = h.objects[size_t(i)];
    ObjectDescription p;
    p.name = o.name;
    p.kind = ObjectKind::Pure;
    p.loc = o.loc;
    p.material = o.material;
    p.base_texture = o.base_texture;
    p.emissive_texture = o.emissive_texture;
    p.cutout = o.cutout;
    if (!o.casts_shadows) p.flags.casts_shadows = false;
    if (!o.receives_shadows) p.flags.receives_shadows = false;
    if (with_triangles) {
      p.triangles.assign(h.triangles.corners.begin() + o.first_triangle,
                         h.triangles.corners.begin() + o.first_triangle + o.triangle_count);
      if (!h.triangles.uv.empty()) {
        p.triangle_uvs.assign(h.triangles.uv.begin() + o.first_triangle,
                              h.triangles.uv.begin() + o.first_triangle + o.triangle_count);
      }
    }
    out.objects.push_back(std::move(p));
    source.resize(out.objects.size(), -1);
    source.back() = i;
    return int32_t(out.objects.size()) - 1;
  }

  // h's lights as objects at the top (already in world space: no transforms).
  void add_lights() {
    for (const Light& l : h.lights) {
      ObjectDescription o;
      o.name = l.name;
      o.loc = l.loc;
      o.light = l;
      out.objects.push_back(std::move(o));
      source.resize(out.objects.size(), -1);
      out.roots.push_back(int32_t(out.objects.size()) - 1);
    }
  }

  int32_t group(ObjectKind kind, std::vector<int32_t> children) {
    ObjectDescription g;
    g.name =
        fmt::format("{} {}", kind == ObjectKind::Composite ? "part" : "group", out.objects.size());
    g.kind = kind;
    g.children = std::move(children);
    out.objects.push_back(std::move(g));
    source.resize(out.objects.size(), -1);
    return int32_t(out.objects.size()) - 1;
  }

  // items: Pure indices of h, sorted however; returns the output object holding them.
  int32_t build(std::vector<int32_t> items) {
    if (items.size() == 1) return pure(items[0]);
    Aabb box, centres;
    for (int32_t i : items) {
      const Aabb& b = h.objects[size_t(i)].box;
      box.extend(b.lo), box.extend(b.hi);
      centres.extend(b.center());
    }
    const float floor = 0.05f * box.diagonal();
    // Compact: the parts fill the box, none is a shell around the others (a room's walls would
    // make any group inside them look full), and none is much denser in triangles than the
    // group (one grid over a plant and a sofa would give the plant's leaves a few crowded cells:
    // the teapot in a stadium).
    double filled = 0.0, largest = 0.0, triangles = 0.0, densest = 0.0;
    for (int32_t i : items) {
      const SceneObject& o = h.objects[size_t(i)];
      const double v = volume(o.box, floor);
      filled += v, largest = std::max(largest, v);
      triangles += o.triangle_count;
      densest = std::max(densest, o.triangle_count / v);
    }
    const double whole = volume(box, floor);
    if (items.size() <= kMaxCompositeParts && filled >= kMinFill * whole &&
        largest <= kMaxShare * whole && densest <= kMaxDensity * triangles / whole) {
      std::vector<int32_t> parts;
      for (int32_t i : items) parts.push_back(pure(i));
      return group(ObjectKind::Composite, std::move(parts));
    }
    // Split at the median along the widest spread of centres (ties by index: deterministic).
    const int axis = centres.widest_axis();
    const size_t half = items.size() / 2;
    std::nth_element(items.begin(), items.begin() + std::ptrdiff_t(half), items.end(),
                     [&](int32_t a, int32_t b) {
                       const float ca = h.objects[size_t(a)].box.center()[axis];
                       const float cb = h.objects[size_t(b)].box.center()[axis];
                       return ca < cb || (ca == cb && a < b);
                     });
    std::vector<int32_t> low(items.begin(), items.begin() + std::ptrdiff_t(half));
    std::vector<int32_t> high(items.begin() + std::ptrdiff_t(half), items.end());
    std::sort(low.begin(), low.end());
    std::sort(high.begin(), high.end());
    const int32_t a = build(std::move(low));
    const int32_t b = build(std::move(high));
    return group(ObjectKind::Assembly, {a, b});
  }
};

// What build_hierarchy makes of a regrouped description, made from the hierarchy it was
// regrouped from: each Pure's triangles, normals and areas copied in the new depth-first order
// rather than computed again (a second build would be a fifth of a million-triangle model's
// import).
// A regrouped scene has no transforms, copies or Lights lists, and its Pures carry their flags.
struct Placer {
  const Hierarchy& from;
  const SceneDescription& d;
  const std::vector<int32_t>& source;
  Hierarchy& out;

  int32_t add(int32_t di, int32_t parent) {
    const ObjectDescription& o = d.objects[size_t(di)];
    const int32_t id = int32_t(out.objects.size());
    out.objects.push_back({});
    out.objects.back().name = o.name;
    out.objects.back().kind = o.kind;
    out.objects.back().loc = o.loc;
    out.objects.back().parent = parent;
    const uint32_t first = uint32_t(out.triangles.size());
    Aabb box;
    if (o.kind == ObjectKind::Pure) {
      const SceneObject& p = from.objects[size_t(source[size_t(di)])];
      const Triangles& f = from.triangles;
      Triangles& t = out.triangles;
      const auto b = long(p.first_triangle), e = b + long(p.triangle_count);
      t.corners.insert(t.corners.end(), f.corners.begin() + b, f.corners.begin() + e);
      t.normal.insert(t.normal.end(), f.normal.begin() + b, f.normal.begin() + e);
      t.area.insert(t.area.end(), f.area.begin() + b, f.area.begin() + e);
      t.object.resize(t.corners.size(), id);
      if (!f.uv.empty()) {
        t.uv.resize(uint32_t(t.corners.size()) - p.triangle_count, kNoTextureCoordinates);
        t.uv.insert(t.uv.end(), f.uv.begin() + b, f.uv.begin() + e);
      }
      SceneObject& s = out.objects.back();
      s.material = p.material;
      s.base_texture = p.base_texture;
      s.emissive_texture = p.emissive_texture;
      s.cutout = p.cutout;
      s.casts_shadows = p.casts_shadows;
      s.receives_shadows = p.receives_shadows;
      s.two_sided = p.two_sided;  // for the summary: its triangles already face both ways
      s.group = p.group;
      box = p.box;
    } else {
      for (const int32_t c : o.children) {
        const int32_t child = add(c, id);
        out.objects[size_t(id)].children.push_back(child);
        box.extend(out.objects[size_t(child)].box);
      }
    }
    SceneObject& s = out.objects[size_t(id)];
    s.box = box;
    s.first_triangle = first;
    s.triangle_count = uint32_t(out.triangles.size()) - first;
    return id;
  }
};

std::vector<int32_t> pures_of(const Hierarchy& h) {
  std::vector<int32_t> p;
  for (size_t i = 0; i < h.objects.size(); ++i) {
    if (h.objects[i].kind == ObjectKind::Pure) p.push_back(int32_t(i));  // never empty (built)
  }
  return p;
}

// h's Pures regrouped as `mode` (Automatic or Flat) says; see automatic_hierarchy in the header.
Regrouper regrouped_pures(const Hierarchy& h, HierarchyMode mode, bool with_triangles) {
  Regrouper r(h, mode == HierarchyMode::Automatic ? "auto" : "flat");
  r.with_triangles = with_triangles;
  const std::vector<int32_t> pures = pures_of(h);
  if (pures.empty()) {
  } else if (mode == HierarchyMode::Automatic) {
    r.out.roots.push_back(r.build(pures));
  } else {
    std::vector<int32_t> parts;
    for (const int32_t i : pures) parts.push_back(r.pure(i));
    r.out.roots.push_back(r.group(ObjectKind::Composite, std::move(parts)));
  }
  r.add_lights();
  return r;
}

}  // namespace

HierarchyMode parse_hierarchy_mode(const std::string& text) {
  if (text == "file") return HierarchyMode::AsRead;
  if (text == "auto") return HierarchyMode::Automatic;
  if (text == "flat") return HierarchyMode::Flat;
  throw Error("expected file, auto or flat, got '" + text + "'");
}

const char* to_string(HierarchyMode mode) {
  switch (mode) {
    case HierarchyMode::AsRead:
      return "file";
    case HierarchyMode::Automatic:
      return "auto";
    case HierarchyMode::Flat:
      return "flat";
  }
  return "?";
}

HierarchyMode default_hierarchy_mode(const std::string& scene_path) {
  return is_model_file(scene_path) ? HierarchyMode::Automatic : HierarchyMode::AsRead;
}

SceneDescription automatic_hierarchy(const Hierarchy& h) {
  return std::move(regrouped_pures(h, HierarchyMode::Automatic, true).out);
}

SceneDescription flat_hierarchy(const Hierarchy& h) {
  return std::move(regrouped_pures(h, HierarchyMode::Flat, true).out);
}

SceneDescription regroup(const SceneDescription& scene, HierarchyMode mode) {
  if (mode == HierarchyMode::AsRead) return scene;
  const Hierarchy h = build_hierarchy(scene);
  return mode == HierarchyMode::Automatic ? automatic_hierarchy(h) : flat_hierarchy(h);
}

Hierarchy regrouped_hierarchy(const Hierarchy& h, HierarchyMode mode) {
  if (mode == HierarchyMode::AsRead) return h;
  const Regrouper r = regrouped_pures(h, mode, false);
  Hierarchy out;
  out.scene_name = h.scene_name;
  out.source_path = h.source_path;
  out.dropped_degenerate = h.dropped_degenerate;
  out.model = h.model;
  out.lights = h.lights;
  out.objects.reserve(r.out.objects.size());
  out.triangles.corners.reserve(h.triangles.size());
  out.triangles.normal.reserve(h.triangles.size());
  out.triangles.area.reserve(h.triangles.size());
  out.triangles.object.reserve(h.triangles.size());
  Placer placer{h, r.out, r.source, out};
  for (const int32_t root : r.out.roots) {
    if (r.out.objects[size_t(root)].light) continue;  // in out.lights already
    out.roots.push_back(placer.add(root, -1));
    out.bounds.extend(out.objects[size_t(out.roots.back())].box);
  }
  return out;
}

Hierarchy build_hierarchy(const SceneDescription& scene, HierarchyMode mode) {
  if (mode == HierarchyMode::AsRead) return build_hierarchy(scene);
  return regrouped_hierarchy(build_hierarchy(scene), mode);
}

Hierarchy load_hierarchy(const std::string& path, const ModelOptions& model,
                         std::optional<HierarchyMode> mode) {
  const HierarchyMode m = mode.value_or(default_hierarchy_mode(path));
  if (m == HierarchyMode::AsRead) return build_hierarchy(read_scene_file(path, model));
  // The description is let go before regrouping: a million-triangle model's peak holds one
  // copy of its triangles less.
  const Hierarchy as_read = build_hierarchy(read_scene_file(path, model));
  return regrouped_hierarchy(as_read, m);
}

}  // namespace rad
