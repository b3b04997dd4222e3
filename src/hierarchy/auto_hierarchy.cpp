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
  }

  // Pure `i` of h as a Pure of the output, its resolved flags written on it.
  int32_t pure(int32_t i) {
    const SceneObject& o = h.objects[size_t(i)];
    ObjectDescription p;
    p.name = o.name;
    p.kind = ObjectKind::Pure;
    p.loc = o.loc;
    p.material = o.material;
    if (!o.casts_shadows) p.flags.casts_shadows = false;
    if (!o.receives_shadows) p.flags.receives_shadows = false;
    p.triangles.assign(h.triangles.corners.begin() + o.first_triangle,
                       h.triangles.corners.begin() + o.first_triangle + o.triangle_count);
    out.objects.push_back(std::move(p));
    return int32_t(out.objects.size()) - 1;
  }

  int32_t group(ObjectKind kind, std::vector<int32_t> children) {
    ObjectDescription g;
    g.name =
        fmt::format("{} {}", kind == ObjectKind::Composite ? "part" : "group", out.objects.size());
    g.kind = kind;
    g.children = std::move(children);
    out.objects.push_back(std::move(g));
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
    const Vec3 spread = centres.extent();
    const int axis =
        spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
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

std::vector<int32_t> pures_of(const Hierarchy& h) {
  std::vector<int32_t> p;
  for (size_t i = 0; i < h.objects.size(); ++i) {
    if (h.objects[i].kind == ObjectKind::Pure) p.push_back(int32_t(i));  // never empty (built)
  }
  return p;
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
  Regrouper r(h, "auto");
  const std::vector<int32_t> pures = pures_of(h);
  if (!pures.empty()) r.out.roots.push_back(r.build(pures));
  return std::move(r.out);
}

SceneDescription flat_hierarchy(const Hierarchy& h) {
  Regrouper r(h, "flat");
  std::vector<int32_t> parts;
  for (int32_t i : pures_of(h)) parts.push_back(r.pure(i));
  if (!parts.empty()) r.out.roots.push_back(r.group(ObjectKind::Composite, std::move(parts)));
  return std::move(r.out);
}

SceneDescription regroup(const SceneDescription& scene, HierarchyMode mode) {
  if (mode == HierarchyMode::AsRead) return scene;
  const Hierarchy h = build_hierarchy(scene);
  return mode == HierarchyMode::Automatic ? automatic_hierarchy(h) : flat_hierarchy(h);
}

Hierarchy build_hierarchy(const SceneDescription& scene, HierarchyMode mode) {
  if (mode == HierarchyMode::AsRead) return build_hierarchy(scene);
  // The first build (in regroup) has said what there is to say about the scene.
  return build_hierarchy(regroup(scene, mode), {}, /*warn=*/false);
}

Hierarchy load_hierarchy(const std::string& path, const ModelOptions& model,
                         std::optional<HierarchyMode> mode) {
  return build_hierarchy(read_scene_file(path, model), mode.value_or(default_hierarchy_mode(path)));
}

}  // namespace rad
