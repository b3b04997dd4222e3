#include "hierarchy/hierarchy.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/matrix.hpp>
#include <string_view>
#include <unordered_map>

namespace rad {

namespace {

struct Builder {
  const SceneDescription& scene;
  Hierarchy& out;
  BuildLimits limits;
  uint32_t dropped = 0;

  std::vector<ObjectFlags> flags_of{};  // per hierarchy object: its flags, a copy's merged

  // Depth-first: a Pure appends its triangles, so every subtree's triangles are contiguous.
  // `outer` maps the parent's coordinates to the world's.
  int32_t add(int32_t desc_index, int32_t parent, const glm::dmat4& outer, int depth) {
    const ObjectDescription& d = scene.objects[size_t(desc_index)];
    // A copy (of a copy...) is its original's contents under both transforms; its own flags win.
    glm::dmat4 placement = outer * transform_matrix(d.transforms);
    ObjectFlags flags = d.flags;
    const ObjectDescription* content = &d;
    while (content->copy_of >= 0) {
      content = &scene.objects[size_t(content->copy_of)];
      placement = placement * transform_matrix(content->transforms);
      if (!flags.casts_shadows) flags.casts_shadows = content->flags.casts_shadows;
      if (!flags.receives_shadows) flags.receives_shadows = content->flags.receives_shadows;
      if (!flags.two_sided) flags.two_sided = content->flags.two_sided;
      if (!flags.has_lights)
        flags.has_lights = content->flags.has_lights, flags.lights = content->flags.lights;
      if (!flags.group) flags.group = content->flags.group;
    }
    // Copies can nest and multiply: bound the walk and what it makes, not the stack or memory.
    if (depth > limits.max_depth || out.objects.size() + out.lights.size() >= limits.max_objects) {
      throw Error(d.loc, fmt::format("copies of copies make more than {} objects or nest deeper "
                                     "than {}",
                                     limits.max_objects, limits.max_depth));
    }
    if (content->light) {  // a light: placed into Hierarchy::lights, no SceneObject
      out.lights.push_back(placed(*content->light, placement, d));
      // Without a Group of its own, the light is in its copy's group, else its enclosing
      // objects'.
      std::string& group = out.lights.back().group;
      if (group.empty())
        group = flags.group.value_or(parent >= 0 ? out.objects[size_t(parent)].group : "");
      return -1;
    }
    int32_t id = static_cast<int32_t>(out.objects.size());
    out.objects.push_back({});
    {
      SceneObject& o = out.objects.back();
      o.name = d.name;
      o.kind = content->kind;
      o.loc = d.loc;
      o.parent = parent;
      o.material = content->material;
      o.base_texture = content->base_texture;
      o.emissive_texture = content->emissive_texture;
      o.cutout = content->cutout;
      o.first_triangle = static_cast<uint32_t>(out.triangles.size());
      const SceneObject* up = parent >= 0 ? &out.objects[size_t(parent)] : nullptr;
      o.casts_shadows = flags.casts_shadows.value_or(up ? up->casts_shadows : true);
      o.receives_shadows = flags.receives_shadows.value_or(up ? up->receives_shadows : true);
      o.two_sided = flags.two_sided.value_or(up ? up->two_sided : false);
      o.influence = flags.has_lights ? id : (up ? up->influence : -1);
      o.group = flags.group.value_or(up ? up->group : std::string());
    }
    flags_of.push_back(std::move(flags));
    const bool identity = placement == glm::dmat4(1.0);
    // A mirroring placement turns every triangle over: swapping two corners keeps its front.
    const bool mirrored = glm::determinant(placement) < 0.0;
    Aabb box;
    if (content->kind == ObjectKind::Pure) {
      if (out.triangles.size() + content->triangles.size() > limits.max_triangles) {
        throw Error(d.loc,
                    fmt::format("the scene places more than {} triangles", limits.max_triangles));
      }
      for (size_t i = 0; i < content->triangles.size(); ++i) {
        auto t = content->triangles[i];
        const SourceLoc& where =
            i < content->triangle_locs.size() ? content->triangle_locs[i] : d.loc;
        if (!identity) {
          for (Vec3& p : t) p = Vec3(DVec3(placement * glm::dvec4(DVec3(p), 1.0)));
          if (mirrored) std::swap(t[1], t[2]);
        }
        // The solver's kernels take distances to the fourth power in single precision.
        for (const Vec3& p : t) {
          if (!(max_component(glm::abs(p)) <= kMaxCoordinate)) {
            throw Error(where,
                        fmt::format("coordinate {:g} {:g} {:g} of Pure \"{}\" is too large: rad "
                                    "computes in single precision and takes |x|, |y|, |z| up to "
                                    "{:g} (scale the scene down)",
                                    p.x, p.y, p.z, d.name, double(kMaxCoordinate)));
          }
        }
        // In double: the cross product of large edges overflows a float.
        const DVec3 nd = glm::cross(DVec3(t[1] - t[0]), DVec3(t[2] - t[0]));
        const double len = glm::length(nd);
        const float area = float(0.5 * len);
        if (!(area > 0.0f) || !std::isfinite(area)) {
          ++dropped;
          continue;
        }
        const Vec3 n(nd / len);
        if (i < content->triangle_uvs.size()) {
          std::array<Vec2, 3> uv = content->triangle_uvs[i];
          if (!identity && mirrored) std::swap(uv[1], uv[2]);
          out.triangles.uv.resize(out.triangles.size(), kNoTextureCoordinates);
          out.triangles.uv.push_back(uv);
        } else if (!out.triangles.uv.empty()) {
          out.triangles.uv.push_back(kNoTextureCoordinates);
        }
        out.triangles.corners.push_back(t);
        out.triangles.normal.push_back(n);
        out.triangles.area.push_back(area);
        out.triangles.object.push_back(id);
        for (const Vec3& p : t) box.extend(p);
      }
      // Each side its own polygon: the same triangles turned over, after them.
      if (out.objects[size_t(id)].two_sided) {
        Triangles& tris = out.triangles;
        const size_t first = out.objects[size_t(id)].first_triangle, end = tris.size();
        if (end + (end - first) > limits.max_triangles) {
          throw Error(d.loc,
                      fmt::format("the scene places more than {} triangles", limits.max_triangles));
        }
        for (size_t i = first; i < end; ++i) {
          const std::array<Vec3, 3> c = tris.corners[i];
          tris.corners.push_back({c[0], c[2], c[1]});
          tris.normal.push_back(-tris.normal[i]);
          tris.area.push_back(tris.area[i]);
          tris.object.push_back(id);
          if (!tris.uv.empty()) {
            const std::array<Vec2, 3> uv = tris.uv[i];
            tris.uv.push_back({uv[0], uv[2], uv[1]});
          }
        }
      }
    } else {
      const size_t lights_before = out.lights.size();
      for (int32_t c : content->children) {
        int32_t child = add(c, id, placement, depth + 1);
        if (child < 0) continue;  // a light
        out.objects[size_t(id)].children.push_back(child);
        box.extend(out.objects[size_t(child)].box);
      }
      // A group of lights alone (an Assembly "lamps" of Light objects) leaves its lights and
      // no object: every object below it was a light, so it is the last object made.
      if (out.triangles.size() == out.objects[size_t(id)].first_triangle &&
          out.lights.size() > lights_before) {
        out.objects.pop_back();
        flags_of.pop_back();
        return -1;
      }
    }
    SceneObject& o = out.objects[size_t(id)];
    o.box = box;
    o.triangle_count = static_cast<uint32_t>(out.triangles.size()) - o.first_triangle;
    if (o.triangle_count == 0) {
      throw Error(d.loc, fmt::format("{} \"{}\" has no triangles of non-zero area (the corners "
                                     "of each lie on a line): give it a surface or remove it",
                                     to_string(o.kind), d.name));
    }
    return id;
  }

  // Light `l` of description object `d` placed by `m` into the world: its position as a point,
  // its direction and C0 direction as directions (unit again); cones, intensity and colour stay
  // as they are (a scale moves a light, it does not brighten or widen it).
  static Light placed(const Light& l, const glm::dmat4& m, const ObjectDescription& d) {
    Light w = l;
    w.name = d.name;
    w.loc = d.loc;
    if (m != glm::dmat4(1.0)) {
      w.position = Vec3(DVec3(m * glm::dvec4(DVec3(l.position), 1.0)));
      const glm::dmat3 linear(m);
      const DVec3 dir = linear * DVec3(l.direction);
      if (glm::length(dir) > 0.0) w.direction = Vec3(glm::normalize(dir));
      DVec3 up = linear * DVec3(l.photometric_up);
      up -= DVec3(w.direction) * glm::dot(up, DVec3(w.direction));
      w.photometric_up =
          glm::length(up) > 1e-6 ? Vec3(glm::normalize(up)) : default_photometric_up(w.direction);
    }
    if (w.kind != LightKind::Directional &&
        !(max_component(glm::abs(w.position)) <= kMaxCoordinate)) {
      throw Error(d.loc, fmt::format("light \"{}\" is placed at {:g} {:g} {:g}, too far: rad takes "
                                     "|x|, |y|, |z| up to {:g} (scale the scene down)",
                                     d.name, w.position.x, w.position.y, w.position.z,
                                     double(kMaxCoordinate)));
    }
    return w;
  }

  // Every object with a Lights list: its own triangles and those of every object of each name
  // it lists, as sorted, merged ranges.
  void resolve_lights() {
    std::unordered_map<std::string_view, std::vector<int32_t>> by_name;
    for (size_t i = 0; i < out.objects.size(); ++i)
      by_name[out.objects[i].name].push_back(int32_t(i));
    for (size_t i = 0; i < out.objects.size(); ++i) {
      const ObjectFlags& f = flags_of[i];
      if (!f.has_lights) continue;
      std::vector<TriangleRange> r;
      auto range_of = [&](int32_t o) {
        r.push_back({out.objects[o].first_triangle, out.objects[o].triangle_count});
      };
      range_of(int32_t(i));
      for (const NamedObject& n : f.lights) {
        auto it = by_name.find(n.name);
        if (it == by_name.end()) {
          throw Error(n.loc, fmt::format("\"{}\" lights \"{}\", but no object has that name",
                                         out.objects[i].name, n.name));
        }
        for (int32_t o : it->second) range_of(o);
      }
      std::sort(r.begin(), r.end(),
                [](const TriangleRange& a, const TriangleRange& b) { return a.first < b.first; });
      std::vector<TriangleRange>& lit = out.objects[i].lit;
      for (const TriangleRange& x : r) {
        if (!lit.empty() && x.first <= lit.back().first + lit.back().count) {
          const uint32_t end = std::max(lit.back().first + lit.back().count, x.first + x.count);
          lit.back().count = end - lit.back().first;
        } else {
          lit.push_back(x);
        }
      }
    }
  }
};

}  // namespace

bool influence_reaches(const Hierarchy& h, int32_t influence, uint32_t t) {
  if (influence < 0) return true;
  const std::vector<TriangleRange>& lit = h.objects[size_t(influence)].lit;
  // The last range starting at or before t.
  auto it = std::upper_bound(lit.begin(), lit.end(), t,
                             [](uint32_t v, const TriangleRange& r) { return v < r.first; });
  return it != lit.begin() && t - std::prev(it)->first < std::prev(it)->count;
}

Hierarchy build_hierarchy(const SceneDescription& scene, const BuildLimits& limits, bool warn) {
  Hierarchy h;
  h.scene_name = scene.name;
  h.source_path = scene.path;
  h.model = scene.model;
  Builder b{scene, h, limits};
  // The triangles as written (copies place more): one allocation for a model of a million.
  size_t written = 0;
  for (const ObjectDescription& o : scene.objects) written += o.triangles.size();
  written = std::min(written, size_t(limits.max_triangles));
  h.triangles.corners.reserve(written);
  h.triangles.normal.reserve(written);
  h.triangles.area.reserve(written);
  h.triangles.object.reserve(written);
  h.objects.reserve(scene.objects.size());
  for (int32_t r : scene.roots) {
    int32_t id = b.add(r, -1, glm::dmat4(1.0), 0);
    if (id < 0) continue;  // a light
    h.roots.push_back(id);
    h.bounds.extend(h.objects[id].box);
  }
  if (h.roots.empty() && !h.lights.empty()) {
    throw Error(SourceLoc{scene.path},
                "the scene has lights but no surfaces for them to light: "
                "give it objects with triangles");
  }
  h.dropped_degenerate = b.dropped;
  b.resolve_lights();
  // Shadow rays leave their surfaces by 1e-5 of the diagonal (visibility/segment.h); beyond 10
  // diagonals from the origin that is under 8 float steps of the coordinates, and the backends'
  // answers near surfaces come down to rounding: they may disagree on a ray in thousands.
  if (warn && h.bounds.diagonal() > 0.0f && h.bounds.magnitude() > 10.0f * h.bounds.diagonal()) {
    rad::warn(
        {scene.path},
        fmt::format("the scene lies {:.0f} times its size from the origin, where float precision "
                    "is too coarse for its shadow rays; move it near the origin",
                    double(h.bounds.magnitude() / h.bounds.diagonal())));
  }
  if (warn && b.dropped > 0) {
    rad::warn({scene.path}, fmt::format("dropped {} degenerate (zero-area) triangle{}", b.dropped,
                                        b.dropped == 1 ? "" : "s"));
  }
  return h;
}

bool is_pure(const Hierarchy& h, int64_t object) {
  return object >= 0 && size_t(object) < h.objects.size() &&
         h.objects[size_t(object)].kind == ObjectKind::Pure;
}

namespace {
constexpr size_t kListedMaterials = 12;
}  // namespace

std::string summarize(const Hierarchy& h) {
  size_t counts[3] = {0, 0, 0};
  size_t emitters = 0, emitting_triangles = 0;
  double emitted_power = 0.0;
  for (const SceneObject& o : h.objects) {
    ++counts[static_cast<int>(o.kind)];
    if (o.kind == ObjectKind::Pure && max_component(o.material.emission) > 0.0f) {
      ++emitters;
      emitting_triangles += o.triangle_count;
      for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t) {
        emitted_power += double(mean_component(o.material.emission)) * h.triangles.area[t];
      }
    }
  }
  std::string s;
  s += fmt::format("Scene \"{}\" ({})\n", h.scene_name, h.source_path);
  s += fmt::format("Objects: {} Assemblies, {} Composites, {} Pures\n", counts[0], counts[1],
                   counts[2]);
  s += fmt::format("Triangles: {}", h.triangles.size());
  if (h.dropped_degenerate) s += fmt::format(" ({} degenerate dropped)", h.dropped_degenerate);
  s += "\n";
  s += fmt::format("Emitters: {} Pures, {} triangles, power {:.6g} (mean over channels)\n",
                   emitters, emitting_triangles, emitted_power);
  if (!h.lights.empty()) {
    size_t kinds[3] = {0, 0, 0}, ies = 0;
    for (const Light& l : h.lights)
      ++kinds[static_cast<int>(l.kind)], ies += l.photometry != nullptr;
    s += fmt::format("Lights: {} ({} point, {} spot, {} directional; {} with IES photometry)\n",
                     h.lights.size(), kinds[0], kinds[1], kinds[2], ies);
  }
  size_t no_cast = 0, no_receive = 0, two_sided = 0, cut = 0, lists = 0;
  for (const SceneObject& o : h.objects) {
    if (o.kind == ObjectKind::Pure) {
      no_cast += !o.casts_shadows, no_receive += !o.receives_shadows, two_sided += o.two_sided;
      cut += bool(o.cutout);
    }
    lists += !o.lit.empty();
  }
  if (no_cast + no_receive + two_sided + cut + lists > 0) {
    s += fmt::format(
        "Flags: {} Pures cast no shadows, {} receive none, {} two-sided, {} cut out; {} Lights "
        "lists\n",
        no_cast, no_receive, two_sided, cut, lists);
  }
  if (h.model) {
    // The names are what --emit patterns match: the summary lists them (the first few).
    const std::vector<std::string>& names = h.model->materials;
    std::string listed;
    for (size_t i = 0; i < names.size() && i < kListedMaterials; ++i) {
      listed += (i ? ", " : "") + names[i];
    }
    if (names.size() > kListedMaterials) listed += ", ...";
    s += fmt::format("Materials: {} ({})\n", names.size(), listed);
    s += fmt::format("Textures: {} read (per vertex, averaged over its element), {} unreadable\n",
                     h.model->textures.read, h.model->textures.unread);
  } else {
    // A description gives each Pure its own material: count the distinct ones.
    std::vector<std::array<float, 6>> distinct;
    for (const SceneObject& o : h.objects) {
      if (o.kind != ObjectKind::Pure) continue;
      const Material& m = o.material;
      distinct.push_back({m.reflectance.x, m.reflectance.y, m.reflectance.z, m.emission.x,
                          m.emission.y, m.emission.z});
    }
    std::sort(distinct.begin(), distinct.end());
    s += fmt::format("Materials: {} distinct\n",
                     std::unique(distinct.begin(), distinct.end()) - distinct.begin());
  }
  s += fmt::format("Bounding box: ({:.6g}, {:.6g}, {:.6g}) - ({:.6g}, {:.6g}, {:.6g})\n",
                   h.bounds.lo.x, h.bounds.lo.y, h.bounds.lo.z, h.bounds.hi.x, h.bounds.hi.y,
                   h.bounds.hi.z);
  return s;
}

}  // namespace rad
