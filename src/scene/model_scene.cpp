#include "scene/model_scene.h"

#include <fnmatch.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>

namespace rad {

EmitRule parse_emit_rule(const std::string& text) {
  const size_t eq = text.rfind('=');
  EmitRule r;
  if (eq == std::string::npos || eq == 0) {
    throw Error("--emit expects PATTERN=VALUE (e.g. 'Lamp*=12'), got '" + text + "'");
  }
  r.pattern = text.substr(0, eq);
  const char* b = text.data() + eq + 1;
  const char* e = text.data() + text.size();
  const auto res = std::from_chars(b, e, r.value);
  if (res.ec != std::errc() || res.ptr != e || !std::isfinite(r.value) || r.value < 0.0f) {
    throw Error("--emit '" + text + "': the value must be a number >= 0");
  }
  return r;
}

GroupRule parse_group_rule(const std::string& text) {
  const size_t eq = text.rfind('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
    throw Error("--light-group expects PATTERN=NAME (e.g. 'Lamp*=kitchen'), got '" + text + "'");
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

namespace {

// The command line's rules (--emit, --light-group, --two-sided) name materials, groups and
// lights by one kind of pattern: the shell's.
bool name_matches(const std::string& pattern, const std::string& name) {
  return fnmatch(pattern.c_str(), name.c_str(), 0) == 0;
}

}  // namespace

SceneDescription model_to_scene(Model m, const ModelOptions& o) {
  std::vector<Material> materials;
  std::vector<size_t> rule_uses(o.emit.size(), 0);
  for (const ModelMaterial& mm : m.materials) {
    Material mat{mm.reflectance, mm.emission};
    if (glm::any(glm::greaterThan(mat.reflectance, Vec3(1.0f)))) {
      warn(mm.loc, "material '" + mm.name +
                       "' reflects more than it receives (Kd above 1); "
                       "clamped to 1");
      mat.reflectance = glm::min(mat.reflectance, Vec3(1.0f));
    }
    for (size_t r = 0; r < o.emit.size(); ++r) {
      if (!name_matches(o.emit[r].pattern, mm.name)) continue;
      const float peak = max_component(mm.reflectance);
      const Vec3 c = peak > 0.0f ? mm.reflectance / peak : Vec3(1.0f);
      mat.emission = o.emit[r].value * c;
      ++rule_uses[r];
    }
    materials.push_back(mat);
  }
  auto names = [&] {  // for the messages only: each name once, the first dozen
    std::vector<std::string> seen;
    std::string all;
    for (const ModelMaterial& mm : m.materials) {
      if (std::find(seen.begin(), seen.end(), mm.name) != seen.end()) continue;
      if (seen.size() == 12) return all + ", ...";
      seen.push_back(mm.name);
      all += (seen.size() == 1 ? "" : ", ") + (mm.name.empty() ? "'' (unnamed)" : mm.name);
    }
    return all;
  };
  // Light groups: per material and per light, the last rule matching its name.
  std::vector<size_t> group_uses(o.light_groups.size(), 0);
  auto group_of = [&](const std::string& name) -> std::optional<std::string> {
    std::optional<std::string> g;
    for (size_t r = 0; r < o.light_groups.size(); ++r) {
      if (!name_matches(o.light_groups[r].pattern, name)) continue;
      g = o.light_groups[r].group;
      ++group_uses[r];
    }
    return g;
  };
  std::vector<std::optional<std::string>> material_group;
  for (const ModelMaterial& mm : m.materials) material_group.push_back(group_of(mm.name));
  for (Light& l : m.lights) {
    if (auto g = group_of(l.name)) l.group = *g;
  }
  for (size_t r = 0; r < o.light_groups.size(); ++r) {
    if (group_uses[r] == 0) {
      throw Error(SourceLoc{m.path}, "--light-group '" + o.light_groups[r].pattern +
                                         "' matches no material (" + names() + ") and no light");
    }
  }
  // Two-sided by name: a material wherever it is used, a group (OBJ o/g, glTF node) whole.
  std::vector<size_t> two_sided_uses(o.two_sided.size(), 0);
  auto two_sided = [&](const std::string& name) {
    bool any = false;
    for (size_t r = 0; r < o.two_sided.size(); ++r) {
      if (!name_matches(o.two_sided[r], name)) continue;
      any = true;
      ++two_sided_uses[r];
    }
    return any;
  };
  std::vector<bool> material_two_sided;
  for (const ModelMaterial& mm : m.materials)
    material_two_sided.push_back(mm.two_sided || two_sided(mm.name));
  std::vector<bool> group_two_sided;
  for (const ModelGroup& g : m.groups) group_two_sided.push_back(two_sided(g.name));
  for (size_t r = 0; r < o.two_sided.size(); ++r) {
    if (two_sided_uses[r] == 0) {
      throw Error(SourceLoc{m.path}, "--two-sided '" + o.two_sided[r] + "' matches no material (" +
                                         names() +
                                         ") and no group; give one of their names or a pattern "
                                         "such as 'Leaf*'");
    }
  }
  for (size_t r = 0; r < o.emit.size(); ++r) {
    if (rule_uses[r] == 0) {
      throw Error(SourceLoc{m.path},
                  "--emit '" + o.emit[r].pattern + "' matches no material (" + names() + ")");
    }
  }

  SceneDescription d;
  d.path = m.path;
  d.name = std::filesystem::path(m.path).stem().string();
  ObjectDescription root;
  root.name = d.name;
  root.kind = ObjectKind::Assembly;
  root.loc = SourceLoc{m.path};
  d.objects.push_back(root);
  d.roots.push_back(0);
  bool emits = false;
  // Each group's Pure per material, reset after the group for the materials it used: a model
  // of many groups and many materials (a converted building: 16k of each) costs their sum, not
  // their product.
  std::vector<int32_t> pure_of(m.materials.size(), -1);
  std::vector<uint32_t> used;
  for (size_t gi = 0; gi < m.groups.size(); ++gi) {
    ModelGroup& g = m.groups[gi];
    for (const uint32_t k : used) pure_of[k] = -1;
    used.clear();
    const int32_t composite = int32_t(d.objects.size());
    ObjectDescription group;
    group.name = g.name;
    group.kind = ObjectKind::Composite;
    group.loc = SourceLoc{m.path};
    d.objects.push_back(std::move(group));
    d.objects[0].children.push_back(composite);
    for (size_t t = 0; t < g.triangles.size(); ++t) {
      const uint32_t k = g.material[t];
      if (pure_of[k] < 0) {
        pure_of[k] = int32_t(d.objects.size());
        used.push_back(k);
        ObjectDescription p;
        p.name = g.name + ": " + m.materials[k].name;
        p.kind = ObjectKind::Pure;
        p.loc = m.materials[k].loc;
        p.material = materials[k];
        p.base_texture = m.materials[k].base_texture;
        p.emissive_texture = m.materials[k].emissive_texture;
        p.cutout = m.materials[k].cutout;
        if (material_two_sided[k] || group_two_sided[gi]) p.flags.two_sided = true;
        p.flags.group = material_group[k];
        emits |= max_component(p.material.emission) > 0.0f;
        d.objects[size_t(composite)].children.push_back(pure_of[k]);
        d.objects.push_back(std::move(p));
      }
      ObjectDescription& p = d.objects[size_t(pure_of[k])];
      // A group of one material (the usual case) hands its triangles over whole.
      if (t == 0 &&
          std::all_of(g.material.begin(), g.material.end(), [&](uint32_t x) { return x == k; })) {
        p.triangles = std::move(g.triangles);
        p.triangle_locs = std::move(g.triangle_locs);
        p.triangle_uvs = std::move(g.triangle_uvs);
        break;
      }
      p.triangles.push_back(g.triangles[t]);
      if (!g.triangle_locs.empty()) p.triangle_locs.push_back(g.triangle_locs[t]);
      if (!g.triangle_uvs.empty()) {
        p.triangle_uvs.resize(p.triangles.size() - 1, kNoTextureCoordinates);
        p.triangle_uvs.push_back(g.triangle_uvs[t]);
      }
    }
  }
  // The model's lights (glTF KHR_lights_punctual), each a Light object of the model's Assembly.
  for (Light& l : m.lights) {
    emits |= l.intensity > 0.0f && max_component(l.colour) > 0.0f;
    ObjectDescription lo;
    lo.name = l.name;
    lo.loc = l.loc;
    lo.light = std::move(l);
    d.objects[0].children.push_back(int32_t(d.objects.size()));
    d.objects.push_back(std::move(lo));
  }
  if (!emits && (o.require_emission || o.warn_unlit)) {
    // The example names the model's own first material: the user copies it and edits the value.
    std::string lamp = "*";
    for (const ModelMaterial& mm : m.materials) {
      if (!mm.name.empty()) {
        lamp = mm.name;
        break;
      }
    }
    const std::string example = "--emit '" + lamp + "=10'";
    if (o.require_emission) {
      throw Error(SourceLoc{m.path},
                  "nothing in this model emits light: name the lamps' materials with --emit, "
                  "e.g. " +
                      example + " (materials: " + names() + ")");
    }
    warn(SourceLoc{m.path},
         "nothing in this model emits light, so a solve will refuse it: name "
         "the lamps' materials with --emit, e.g. " +
             example + " (materials: " + names() + ")");
  }
  ModelSummary summary;
  for (const ModelMaterial& mm : m.materials) summary.materials.push_back(mm.name);
  summary.textures = m.textures;
  d.model = std::move(summary);
  return d;
}

}  // namespace rad
