#include "export/gltf_writer.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "export/texture_png.h"
#include "export/welded_mesh.h"

namespace rad {

namespace {

/// Appends `bytes` to buffer 0 (4-byte aligned) as a new buffer view; returns its index.
int add_view(tinygltf::Model& m, const void* bytes, size_t size, int target) {
  std::vector<unsigned char>& data = m.buffers[0].data;
  while (data.size() % 4 != 0) data.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  view.target = target;
  const auto* b = static_cast<const unsigned char*>(bytes);
  data.insert(data.end(), b, b + size);
  m.bufferViews.push_back(view);
  return int(m.bufferViews.size() - 1);
}

/// A float VEC3 vertex attribute accessor over `v`; returns its index.
int add_vec3(tinygltf::Model& m, const std::vector<Vec3>& v, bool with_bounds) {
  static_assert(sizeof(Vec3) == 3 * sizeof(float), "Vec3 must be three packed floats");
  tinygltf::Accessor a;
  a.bufferView = add_view(m, v.data(), v.size() * sizeof(Vec3), TINYGLTF_TARGET_ARRAY_BUFFER);
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = TINYGLTF_TYPE_VEC3;
  a.count = v.size();
  if (with_bounds) {
    Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const Vec3& p : v) lo = glm::min(lo, p), hi = glm::max(hi, p);
    a.minValues = {lo.x, lo.y, lo.z};
    a.maxValues = {hi.x, hi.y, hi.z};
  }
  m.accessors.push_back(a);
  return int(m.accessors.size() - 1);
}

/// A uint32 index accessor over `indices`; returns its index.
int add_indices(tinygltf::Model& m, const std::vector<uint32_t>& indices) {
  tinygltf::Accessor a;
  a.bufferView = add_view(m, indices.data(), indices.size() * sizeof(uint32_t),
                          TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  a.type = TINYGLTF_TYPE_SCALAR;
  a.count = indices.size();
  m.accessors.push_back(a);
  return int(m.accessors.size() - 1);
}

/// The most a textured file's colours are scaled down to keep COLOR_0 within 0-1.
constexpr float kMaxColourDivisor = 4.0f;

int gltf_wrap(TextureWrap w) {
  switch (w) {
    case TextureWrap::ClampToEdge:
      return TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    case TextureWrap::MirroredRepeat:
      return TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
    case TextureWrap::Repeat:
      break;
  }
  return TINYGLTF_TEXTURE_WRAP_REPEAT;
}

/// One primitive per material over the shared vertex attributes of `base`: the faces without
/// texture under `plain`, and each texture's faces under a copy of it that shows the texture
/// (TEXCOORD_0), cut out where the scene's material was. Each image is embedded once, as PNG.
void add_textured_primitives(tinygltf::Model& m, const OutputMesh& mesh, tinygltf::Primitive base,
                             const tinygltf::Material& plain, tinygltf::Mesh& gm) {
  static_assert(sizeof(Vec2) == 2 * sizeof(float), "Vec2 must be two packed floats");
  tinygltf::Accessor uv;
  uv.bufferView =
      add_view(m, mesh.uv().data(), mesh.uv().size() * sizeof(Vec2), TINYGLTF_TARGET_ARRAY_BUFFER);
  uv.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  uv.type = TINYGLTF_TYPE_VEC2;
  uv.count = mesh.uv().size();
  m.accessors.push_back(uv);
  const int uv_accessor = int(m.accessors.size() - 1);

  const std::vector<OutputTexture>& textures = mesh.textures();
  std::vector<std::vector<uint32_t>> faces(textures.size() + 1);  // [0]: no texture
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    std::vector<uint32_t>& to = faces[size_t(mesh.face_texture()[f] + 1)];
    to.insert(to.end(), &mesh.indices()[3 * f], &mesh.indices()[3 * f + 3]);
  }
  if (!faces[0].empty()) {
    base.indices = add_indices(m, faces[0]);
    m.materials.push_back(plain);
    base.material = int(m.materials.size() - 1);
    gm.primitives.push_back(base);
  }
  std::vector<const TextureImage*> images;  // glTF image i holds images[i]
  std::vector<TextureSampler> samplers;
  std::vector<std::pair<int, int>> gltf_textures;  // (image, sampler)
  auto index_of = [](auto& list, const auto& item, auto same) {
    for (size_t i = 0; i < list.size(); ++i) {
      if (same(list[i], item)) return int(i);
    }
    list.push_back(item);
    return int(list.size() - 1);
  };
  for (size_t k = 0; k < textures.size(); ++k) {
    if (faces[k + 1].empty()) continue;
    const OutputTexture& t = textures[k];
    const size_t images_before = images.size();
    const int image = index_of(images, t.map.image.get(), std::equal_to<>());
    if (images.size() > images_before) {
      const std::string png = encode_png(*t.map.image);
      tinygltf::Image gi;
      gi.bufferView = add_view(m, png.data(), png.size(), 0);
      gi.mimeType = "image/png";
      m.images.push_back(gi);
    }
    const size_t samplers_before = samplers.size();
    const int sampler =
        index_of(samplers, t.map.sampler, [](const TextureSampler& a, const TextureSampler& b) {
          return a.wrap_s == b.wrap_s && a.wrap_t == b.wrap_t && a.nearest == b.nearest;
        });
    if (samplers.size() > samplers_before) {
      tinygltf::Sampler gs;
      gs.magFilter =
          t.map.sampler.nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
      gs.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
      gs.wrapS = gltf_wrap(t.map.sampler.wrap_s);
      gs.wrapT = gltf_wrap(t.map.sampler.wrap_t);
      m.samplers.push_back(gs);
    }
    const size_t textures_before = gltf_textures.size();
    const int texture = index_of(gltf_textures, std::pair(image, sampler), std::equal_to<>());
    if (gltf_textures.size() > textures_before) {
      tinygltf::Texture gt;
      gt.source = image;
      gt.sampler = sampler;
      m.textures.push_back(gt);
    }
    tinygltf::Material mat = plain;
    mat.name = "radiosity on texture " + std::to_string(k) + " (unlit: baseColorTexture x COLOR_0)";
    mat.pbrMetallicRoughness.baseColorTexture.index = texture;
    if (t.mask) {
      mat.alphaMode = "MASK";
      mat.alphaCutoff = t.cutoff;
      mat.pbrMetallicRoughness.baseColorFactor[3] = t.alpha_scale;
    }
    m.materials.push_back(mat);
    tinygltf::Primitive prim = base;
    prim.attributes["TEXCOORD_0"] = uv_accessor;
    prim.indices = add_indices(m, faces[k + 1]);
    prim.material = int(m.materials.size() - 1);
    gm.primitives.push_back(prim);
  }
}

void serialise(tinygltf::Model& m, std::ostream& out, bool binary) {
  if (m.buffers[0].data.empty()) m.buffers.clear();
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&m, out, !binary, binary)) {
    throw Error("glTF serialisation failed");
  }
}

tinygltf::Model empty_model() {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "rad (progressive radiosity)";
  m.buffers.resize(1);
  m.scenes.resize(1);
  m.defaultScene = 0;
  return m;
}

}  // namespace

void write_scene_gltf(std::ostream& out, const Hierarchy& h, bool binary) {
  tinygltf::Model m = empty_model();
  m.scenes[0].name = h.scene_name;
  bool strength = false;
  m.nodes.resize(h.objects.size());
  for (size_t i = 0; i < h.objects.size(); ++i) {
    const SceneObject& o = h.objects[i];
    tinygltf::Node& node = m.nodes[i];
    node.name = o.name;
    node.children.assign(o.children.begin(), o.children.end());
    if (o.kind != ObjectKind::Pure) continue;
    const WeldedMesh w = weld_pure(h, int32_t(i));
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] = add_vec3(m, w.position, true);
    prim.indices = add_indices(m, w.indices);

    tinygltf::Material mat;
    mat.name = o.name;
    const Vec3 rho = o.material.reflectance, e = o.material.emission;
    mat.pbrMetallicRoughness.baseColorFactor = {rho.x, rho.y, rho.z, 1.0};
    mat.pbrMetallicRoughness.metallicFactor = 0.0;
    mat.pbrMetallicRoughness.roughnessFactor = 1.0;
    const float peak = max_component(e);
    if (peak > 0.0f) {
      const Vec3 colour = peak > 1.0f ? e / peak : e;
      mat.emissiveFactor = {colour.x, colour.y, colour.z};
      if (peak > 1.0f) {
        tinygltf::Value::Object ext;
        ext["emissiveStrength"] = tinygltf::Value(double(peak));
        mat.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(ext);
        strength = true;
      }
    }
    m.materials.push_back(mat);
    prim.material = int(m.materials.size() - 1);
    tinygltf::Mesh gm;
    gm.name = o.name;
    gm.primitives.push_back(prim);
    m.meshes.push_back(gm);
    node.mesh = int(m.meshes.size() - 1);
  }
  if (strength) m.extensionsUsed.push_back("KHR_materials_emissive_strength");
  m.scenes[0].nodes.assign(h.roots.begin(), h.roots.end());
  serialise(m, out, binary);
}

void write_gltf(std::ostream& out, const OutputMesh& mesh, const ToneMap& tm, bool binary) {
  tinygltf::Model m = empty_model();
  if (!mesh.indices().empty()) {
    const bool textured = !mesh.textures().empty();
    std::vector<Vec3> colour(mesh.display.size());
    for (size_t v = 0; v < colour.size(); ++v) colour[v] = tone_map(mesh.display[v], tm);
    float scale = 1.0f;
    if (textured) {
      // The viewer multiplies: baseColorTexture x COLOR_0 is the display colour at the vertex.
      float top = 0.0f;
      for (size_t v = 0; v < colour.size(); ++v) {
        for (int k = 0; k < 3; ++k) {
          const float t = mesh.texel[v][k];
          colour[v][k] = t > 0.0f ? colour[v][k] / t : 0.0f;
          top = std::max(top, colour[v][k]);
        }
      }
      // glTF holds COLOR_0 within 0-1, and the light on a texture darker than white can be
      // brighter than that: every colour of the file is scaled down alike (by at most two stops;
      // beyond, the brightest clamp), so the picture keeps its ratios.
      scale = 1.0f / std::clamp(top, 1.0f, kMaxColourDivisor);
      for (Vec3& c : colour) c = glm::min(c * scale, Vec3(1.0f));
    }

    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] = add_vec3(m, mesh.position(), true);
    prim.attributes["COLOR_0"] = add_vec3(m, colour, false);
    prim.attributes["_RADIOSITY"] = add_vec3(m, mesh.radiosity, false);
    for (size_t g = 0; g < mesh.group_radiosity.size(); ++g) {
      prim.attributes["_RADIOSITY_GROUP_" + std::to_string(g)] =
          add_vec3(m, mesh.group_radiosity[g], false);
    }

    tinygltf::Material mat;
    mat.name = "radiosity (unlit vertex colours)";
    mat.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, 1.0};
    mat.pbrMetallicRoughness.metallicFactor = 0.0;
    mat.pbrMetallicRoughness.roughnessFactor = 1.0;
    mat.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object());
    m.extensionsUsed.push_back("KHR_materials_unlit");

    tinygltf::Mesh gm;
    gm.name = "radiosity";
    tinygltf::Value::Object extras;
    if (textured) extras["colour_scale"] = tinygltf::Value(double(scale));
    if (!mesh.group_names.empty()) {
      // _RADIOSITY_GROUP_i is the radiosity of light group light_groups[i] alone.
      tinygltf::Value::Array names;
      for (const std::string& g : mesh.group_names) names.push_back(tinygltf::Value(g));
      extras["light_groups"] = tinygltf::Value(names);
    }
    if (!extras.empty()) gm.extras = tinygltf::Value(extras);
    if (!textured) {
      prim.indices = add_indices(m, mesh.indices());
      m.materials.push_back(mat);
      prim.material = 0;
      gm.primitives.push_back(prim);
    } else {
      add_textured_primitives(m, mesh, prim, mat, gm);
    }
    m.meshes.push_back(gm);
    tinygltf::Node node;
    node.name = "radiosity";
    node.mesh = 0;
    m.nodes.push_back(node);
    m.scenes[0].nodes.push_back(0);
  }
  serialise(m, out, binary);
}

}  // namespace rad
