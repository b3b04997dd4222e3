#include "scene/gltf_reader.h"

// The implementation is Debian's libtinygltf (it decodes images with its own stb_image; rad
// replaces that loader below with its own decoding into linear colour, scene/texture.h).
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "scene/text_file.h"
#include "scene/texture.h"

namespace rad {

namespace {

namespace fs = std::filesystem;

// Node trees may repeat a mesh; a hostile one could place it 2^depth times.
constexpr size_t kMaxTriangles = 50'000'000;
constexpr int kMaxDepth = 256;
constexpr size_t kMaxPlacements = 10'000'000;  // node visits: a node may list one child twice

struct Context {
  std::string folder;  // external files only from here; "" refuses them
  std::string path;    // the file, to name its images
  std::map<int, std::shared_ptr<const TextureImage>> images;  // by image index, decoded once
};

bool load_image(tinygltf::Image* image, const int index, std::string*, std::string* warn, int, int,
                const unsigned char* bytes, int size, void* user) {
  auto* c = static_cast<Context*>(user);
  if (size > 0) {
    const std::string name = !image->uri.empty() && image->uri.compare(0, 5, "data:") != 0
                                 ? image->uri
                                 : "image " + std::to_string(index) + " of " + c->path;
    if (std::shared_ptr<const TextureImage> t = decode_texture(bytes, size_t(size), name)) {
      c->images[index] = std::move(t);
    } else if (warn) {
      *warn += (name == image->uri ? "the image " : "") + name +
               " cannot be decoded (not a PNG, JPEG or other image stb_image reads, or more "
               "than 64 million pixels); its material uses its factor\n";
    }
  }
  image->width = image->height = 1;
  image->component = 3;
  image->image.clear();
  return true;  // an unreadable texture is not worth refusing the scene
}

bool file_exists(const std::string& p, void* user) {
  std::error_code ec;
  return !static_cast<Context*>(user)->folder.empty() && fs::is_regular_file(p, ec);
}
std::string expand_path(const std::string& p, void*) { return p; }
bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& p,
                     void* user) {
  if (static_cast<Context*>(user)->folder.empty()) {
    if (err) *err += "external file " + p + " refused\n";
    return false;
  }
  try {
    const std::string s = read_text_file(p, SourceLoc{p});
    out->assign(s.begin(), s.end());
    return true;
  } catch (const Error& e) {
    if (err) *err += e.message() + "\n";
    return false;
  }
}
bool write_whole_file(std::string*, const std::string&, const std::vector<unsigned char>&, void*) {
  return false;
}

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw Error(SourceLoc{path}, why);
}

// An accessor's elements, checked to lie inside their buffer.
struct View {
  const unsigned char* data = nullptr;
  size_t stride = 0, count = 0;
  int component = 0;  // TINYGLTF_COMPONENT_TYPE_*
  int components = 0;
};

View view(const tinygltf::Model& m, int index, const std::string& path, const char* what) {
  if (index < 0 || size_t(index) >= m.accessors.size())
    fail(path, std::string(what) + ": no such accessor");
  const tinygltf::Accessor& a = m.accessors[size_t(index)];
  if (a.sparse.isSparse) fail(path, std::string(what) + ": sparse accessors are not read");
  if (a.bufferView < 0 || size_t(a.bufferView) >= m.bufferViews.size())
    fail(path, std::string(what) + ": no buffer view");
  const tinygltf::BufferView& bv = m.bufferViews[size_t(a.bufferView)];
  if (bv.buffer < 0 || size_t(bv.buffer) >= m.buffers.size())
    fail(path, std::string(what) + ": no buffer");
  const std::vector<unsigned char>& buffer = m.buffers[size_t(bv.buffer)].data;
  const int csize = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
  const int ncomp = tinygltf::GetNumComponentsInType(uint32_t(a.type));
  if (csize <= 0 || ncomp <= 0) fail(path, std::string(what) + ": unknown component type");
  View v;
  v.component = a.componentType;
  v.components = ncomp;
  v.count = a.count;
  const size_t element = size_t(csize) * size_t(ncomp);
  v.stride = bv.byteStride ? bv.byteStride : element;
  if (v.stride < element) fail(path, std::string(what) + ": byteStride below the element size");
  if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset ||
      a.byteOffset > bv.byteLength) {
    fail(path, std::string(what) + ": buffer view outside its buffer");
  }
  const size_t room = bv.byteLength - a.byteOffset;
  if (v.count > 0 && (room < element || (v.count - 1) > (room - element) / v.stride)) {
    fail(path, std::string(what) + ": accessor runs past its buffer view");
  }
  v.data = buffer.data() + bv.byteOffset + a.byteOffset;
  return v;
}

double component(const View& v, size_t i, int k) {
  const unsigned char* p = v.data + i * v.stride;
  switch (v.component) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p + 4 * k, 4);
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return p[k];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t u;
      std::memcpy(&u, p + 2 * k, 2);
      return u;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t u;
      std::memcpy(&u, p + 4 * k, 4);
      return u;
    }
    default:
      return std::nan("");
  }
}

glm::dmat4 local_transform(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data());
  glm::dmat4 m(1.0);
  if (n.translation.size() == 3)
    m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4) {
    m *= glm::mat4_cast(
        glm::normalize(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2])));
  }
  if (n.scale.size() == 3) m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  return m;
}

// Which texture coordinates a material's base texture reads, and the KHR_texture_transform
// that maps them (u' = offset + R(rotation) S(scale) u, the extension's matrix).
struct TextureCoordinates {
  int set = 0;                                   // TEXCOORD_<set>
  double matrix[2][3] = {{1, 0, 0}, {0, 1, 0}};  // rows: u' and v' of (u, v, 1)
  Vec2 apply(double u, double v) const {
    return Vec2(float(matrix[0][0] * u + matrix[0][1] * v + matrix[0][2]),
                float(matrix[1][0] * u + matrix[1][1] * v + matrix[1][2]));
  }
};

TextureCoordinates coordinates_of(int tex_coord, const tinygltf::ExtensionMap& extensions) {
  TextureCoordinates c;
  c.set = tex_coord;
  const auto ext = extensions.find("KHR_texture_transform");
  if (ext == extensions.end() || !ext->second.IsObject()) return c;
  const tinygltf::Value& x = ext->second;
  auto number = [](const tinygltf::Value& v, double fallback) {
    const double d = v.IsNumber() ? v.GetNumberAsDouble() : fallback;
    return std::isfinite(d) ? d : fallback;
  };
  double offset[2] = {0, 0}, scale[2] = {1, 1};
  for (int k = 0; k < 2; ++k) {
    if (x.Get("offset").IsArray() && x.Get("offset").ArrayLen() == 2)
      offset[k] = number(x.Get("offset").Get(k), 0.0);
    if (x.Get("scale").IsArray() && x.Get("scale").ArrayLen() == 2)
      scale[k] = number(x.Get("scale").Get(k), 1.0);
  }
  const double r = number(x.Get("rotation"), 0.0), cs = std::cos(r), sn = std::sin(r);
  c.matrix[0][0] = cs * scale[0], c.matrix[0][1] = sn * scale[1], c.matrix[0][2] = offset[0];
  c.matrix[1][0] = -sn * scale[0], c.matrix[1][1] = cs * scale[1], c.matrix[1][2] = offset[1];
  if (x.Get("texCoord").IsNumber()) c.set = x.Get("texCoord").GetNumberAsInt();
  return c;
}

TextureWrap wrap_of(int gl) {
  switch (gl) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
      return TextureWrap::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
      return TextureWrap::MirroredRepeat;
    default:
      return TextureWrap::Repeat;
  }
}

ModelMaterial material_of(const tinygltf::Material& g, const Context& c, const tinygltf::Model& m,
                          const std::string& path, TextureCounts& textures,
                          TextureCoordinates& coordinates) {
  ModelMaterial mat;
  mat.name = g.name.empty() ? "material" : g.name;
  mat.loc = SourceLoc{path};
  mat.two_sided = g.doubleSided;
  const auto& f = g.pbrMetallicRoughness.baseColorFactor;
  if (f.size() >= 3) mat.reflectance = Vec3(float(f[0]), float(f[1]), float(f[2]));
  int t = g.pbrMetallicRoughness.baseColorTexture.index;
  coordinates = coordinates_of(g.pbrMetallicRoughness.baseColorTexture.texCoord,
                               g.pbrMetallicRoughness.baseColorTexture.extensions);
  // Older exporters write the specular-glossiness model instead; its diffuse colour is what
  // reflects diffusely, and readers that know the extension take it over the base colour.
  const auto sg = g.extensions.find("KHR_materials_pbrSpecularGlossiness");
  if (sg != g.extensions.end() && sg->second.IsObject()) {
    const tinygltf::Value& d = sg->second.Get("diffuseFactor");
    if (d.IsArray() && d.ArrayLen() >= 3) {
      for (int k = 0; k < 3; ++k) mat.reflectance[k] = float(d.Get(k).GetNumberAsDouble());
    } else {
      mat.reflectance = Vec3(1.0f);  // the extension's default diffuse factor
    }
    const tinygltf::Value& dt = sg->second.Get("diffuseTexture");
    t = dt.IsObject() && dt.Get("index").IsNumber() ? dt.Get("index").GetNumberAsInt() : -1;
    coordinates = coordinates_of(
        dt.IsObject() && dt.Get("texCoord").IsNumber() ? dt.Get("texCoord").GetNumberAsInt() : 0,
        dt.IsObject() && dt.Get("extensions").IsObject()
            ? tinygltf::ExtensionMap{{"KHR_texture_transform",
                                      dt.Get("extensions").Get("KHR_texture_transform")}}
            : tinygltf::ExtensionMap{});
  }
  if (t >= 0 && size_t(t) < m.textures.size()) {
    const tinygltf::Texture& texture = m.textures[size_t(t)];
    const auto it = c.images.find(texture.source);
    if (it != c.images.end()) {
      mat.reflectance *= it->second->mean;
      mat.base_texture.image = it->second;
      if (texture.sampler >= 0 && size_t(texture.sampler) < m.samplers.size()) {
        const tinygltf::Sampler& s = m.samplers[size_t(texture.sampler)];
        mat.base_texture.sampler.wrap_s = wrap_of(s.wrapS);
        mat.base_texture.sampler.wrap_t = wrap_of(s.wrapT);
        mat.base_texture.sampler.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
      }
      // A cut-out: MASK at its cutoff, BLEND (which rad cannot blend) as MASK at 0.5, when some
      // texel can fall below it.
      const float scale = f.size() >= 4 ? float(f[3]) : 1.0f;
      if (g.alphaMode == "MASK" || g.alphaMode == "BLEND") {
        const float cutoff = g.alphaMode == "MASK" ? float(g.alphaCutoff) : 0.5f;
        if ((it->second->has_alpha || scale < cutoff) && std::isfinite(scale) &&
            std::isfinite(cutoff)) {
          mat.cutout = {mat.base_texture, false, scale, cutoff};
        }
      }
      ++textures.read;
    } else {
      ++textures.unread;
    }
  }
  double strength = 1.0;
  const auto ext = g.extensions.find("KHR_materials_emissive_strength");
  if (ext != g.extensions.end() && ext->second.Has("emissiveStrength")) {
    strength = ext->second.Get("emissiveStrength").GetNumberAsDouble();
  }
  if (g.emissiveFactor.size() == 3) {
    mat.emission =
        Vec3(float(g.emissiveFactor[0] * strength), float(g.emissiveFactor[1] * strength),
             float(g.emissiveFactor[2] * strength));
  }
  // The emissive texture, read through the base texture's coordinates when there is one (rad
  // keeps one set per triangle), else through its own.
  const int et = g.emissiveTexture.index;
  if (et >= 0 && size_t(et) < m.textures.size() && max_component(mat.emission) > 0.0f) {
    const auto it = c.images.find(m.textures[size_t(et)].source);
    if (it != c.images.end()) {
      mat.emission *= it->second->mean;
      mat.emissive_texture.image = it->second;
      const int s = m.textures[size_t(et)].sampler;
      if (s >= 0 && size_t(s) < m.samplers.size()) {
        mat.emissive_texture.sampler.wrap_s = wrap_of(m.samplers[size_t(s)].wrapS);
        mat.emissive_texture.sampler.wrap_t = wrap_of(m.samplers[size_t(s)].wrapT);
        mat.emissive_texture.sampler.nearest =
            m.samplers[size_t(s)].magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
      }
      if (!mat.base_texture) {
        coordinates = coordinates_of(g.emissiveTexture.texCoord, g.emissiveTexture.extensions);
      }
      ++textures.read;
    } else {
      ++textures.unread;
    }
  }
  for (int k = 0; k < 3; ++k) {
    if (!(mat.reflectance[k] >= 0.0f && std::isfinite(mat.reflectance[k])) ||
        !(mat.emission[k] >= 0.0f && std::isfinite(mat.emission[k]))) {
      fail(path, "material '" + mat.name + "' has a negative or non-finite colour or emission");
    }
  }
  return mat;
}

// Extensions rad reads (the rest it ignores, with a warning).
constexpr std::string_view kReadExtensions[] = {
    "KHR_texture_transform", "KHR_materials_emissive_strength",
    "KHR_materials_pbrSpecularGlossiness", "KHR_lights_punctual"};

// Extensions a file may require that change where its vertices are: without them rad would
// read wrong or no geometry.
constexpr const char* kGeometryExtensions[] = {"KHR_draco_mesh_compression",
                                               "EXT_meshopt_compression", "KHR_mesh_quantization"};

// Why rad cannot read a file of this version and these required extensions, or "".
std::string unsupported(const std::string& version, const std::vector<std::string>& required) {
  if (!version.empty() && version[0] != '2') {
    return "a glTF " + version +
           " file: rad reads glTF 2.0; upgrade it (e.g. npx gltf-pipeline -i IN -o OUT writes "
           "glTF 2.0)";
  }
  for (const std::string& e : required) {
    for (const char* g : kGeometryExtensions) {
      if (e == g) {
        return "its meshes need the extension " + e +
               ", which rad does not decode; write it without that compression (e.g. npx "
               "@gltf-transform/cli copy IN OUT, or re-export from Blender with compression "
               "off)";
      }
    }
  }
  return "";
}

// The version and required extensions of a file tinygltf refused, read from its JSON: a glTF
// 1.0 or Draco-compressed file fails deep inside tinygltf with a message about an accessor.
std::string unsupported_in_json(std::string_view bytes, bool binary) {
  uint32_t word[5] = {0, 0, 0, 0, 0};
  std::memcpy(word, bytes.data(), std::min(bytes.size(), sizeof word));
  if (binary && word[1] == 1) return unsupported(std::string("1.0"), {});
  std::string_view text = bytes;
  if (binary) {  // the first chunk, after the 12-byte header and its own 8 bytes, is the JSON
    if (bytes.size() < 20 || word[3] > bytes.size() - 20) return "";
    text = bytes.substr(20, word[3]);
  }
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_object()) return "";
  std::string version;
  const auto asset = j.find("asset");
  if (asset != j.end() && asset->is_object()) {
    const auto v = asset->find("version");
    if (v != asset->end())
      version = v->is_string() ? v->get<std::string>()
                               : v->dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  }
  // glTF 1.0 keeps meshes, nodes and accessors in objects by id, 2.0 in arrays.
  const auto meshes = j.find("meshes");
  if (meshes != j.end() && meshes->is_object() && version.empty()) version = "1.0";
  std::vector<std::string> required;
  const auto r = j.find("extensionsRequired");
  if (r != j.end() && r->is_array()) {
    for (const nlohmann::json& e : *r) {
      if (e.is_string()) required.push_back(e.get<std::string>());
    }
  }
  return unsupported(version, required);
}

// A KHR_lights_punctual light placed by its node's world matrix: at the node's origin, shining
// along its -Z axis (the C0 direction of a photometry, unused by glTF, along its +X).
Light light_of(const tinygltf::Light& gl, int index, const std::string& node_name,
               const glm::dmat4& world, const std::string& path, bool& range_warned) {
  Light l;
  l.name = !gl.name.empty()     ? gl.name
           : !node_name.empty() ? node_name
                                : "light " + std::to_string(index);
  l.loc = SourceLoc{path};
  const std::string who =
      "KHR_lights_punctual light " + std::to_string(index) + " ('" + l.name + "')";
  if (gl.type == "point") {
    l.kind = LightKind::Point;
  } else if (gl.type == "spot") {
    l.kind = LightKind::Spot;
  } else if (gl.type == "directional") {
    l.kind = LightKind::Directional;
  } else {
    fail(path, who + " has type '" + gl.type.substr(0, 40) +
                   "': the extension's lights are point, spot or directional");
  }
  if (!gl.color.empty()) {
    if (gl.color.size() != 3) fail(path, who + ": its color must have 3 components");
    l.colour = Vec3(float(gl.color[0]), float(gl.color[1]), float(gl.color[2]));
  }
  l.intensity = float(gl.intensity);
  if (l.kind == LightKind::Spot) {
    l.inner_cone = float(gl.spot.innerConeAngle);
    l.outer_cone = float(gl.spot.outerConeAngle);
  }
  if (gl.range > 0.0 && !range_warned) {
    range_warned = true;
    rad::warn(SourceLoc{path}, who +
                                   " has a range, which rad ignores: light falls off with the "
                                   "square of the distance and reaches as far as it goes");
  }
  l.position = Vec3(DVec3(world * glm::dvec4(0.0, 0.0, 0.0, 1.0)));
  const glm::dmat3 linear(world);
  const DVec3 d = linear * DVec3(0.0, 0.0, -1.0);
  if (glm::length(d) > 0.0 && std::isfinite(glm::length(d))) {
    l.direction = Vec3(glm::normalize(d));
  } else if (l.kind == LightKind::Point) {
    l.direction = Vec3(0.0f, -1.0f, 0.0f);
  }
  DVec3 up = linear * DVec3(1.0, 0.0, 0.0);
  up -= DVec3(l.direction) * glm::dot(up, DVec3(l.direction));
  l.photometric_up = glm::length(up) > 1e-9 && std::isfinite(glm::length(up))
                         ? Vec3(glm::normalize(up))
                         : default_photometric_up(l.direction);
  try {
    check_light(l);
  } catch (const Error& e) {
    fail(path, who + " (node '" + node_name + "'): " + e.message());
  }
  return l;
}

}  // namespace

Model parse_gltf(std::string_view bytes, const std::string& path, const std::string& folder) {
  Context c{folder, path, {}};
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(load_image, &c);
  loader.SetFsCallbacks({file_exists, expand_path, read_whole_file, write_whole_file, &c});
  tinygltf::Model g;
  std::string err, warn;
  const bool binary = bytes.size() >= 4 && bytes.substr(0, 4) == "glTF";
  if (bytes.size() > 0xffffffffu) fail(path, "larger than 4 GiB");
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(&g, &err, &warn,
                                           reinterpret_cast<const unsigned char*>(bytes.data()),
                                           unsigned(bytes.size()), folder)
             : loader.LoadASCIIFromString(&g, &err, &warn, bytes.data(), unsigned(bytes.size()),
                                          folder);
  if (!ok) {
    const std::string why = unsupported_in_json(bytes, binary);
    fail(path, !why.empty() ? why : "not a readable glTF file: " + err.substr(0, err.find('\n')));
  }
  if (const std::string why = unsupported(g.asset.version, g.extensionsRequired); !why.empty()) {
    fail(path, why);
  }
  // Every line tinygltf and the image loader wrote (a missing image adds two), each once.
  std::vector<std::string_view> said;
  for (size_t at = 0; at < warn.size();) {
    const size_t end = std::min(warn.find('\n', at), warn.size());
    const std::string_view line = std::string_view(warn).substr(at, end - at);
    at = end + 1;
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    if (std::find(said.begin(), said.end(), line) != said.end()) continue;
    said.push_back(line);
    // tinygltf follows a missing image's "File not found" with a line naming it by index.
    constexpr std::string_view kFailed = "Failed to load external 'uri' for image[";
    if (line.substr(0, kFailed.size()) == kFailed) {
      const size_t image = size_t(std::atoll(std::string(line.substr(kFailed.size())).c_str()));
      if (image < g.images.size()) {
        rad::warn(SourceLoc{path}, "the image " + g.images[image].uri +
                                       " is not read; its material uses its factor");
        continue;
      }
    }
    rad::warn(SourceLoc{path}, std::string(line));
  }
  // Any other required extension changes how materials look, not where surfaces are: the file
  // is read without it, once said.
  for (const std::string& e : g.extensionsRequired) {
    if (e == "KHR_lights_punctual") continue;  // read
    rad::warn(SourceLoc{path}, "the extension " + e +
                                   " is required but rad ignores it: materials take their base "
                                   "colour and emission alone");
  }

  // Used, not required: the file reads without them, and a reader that ignores them shows less
  // (a clearcoat, a transmission, a sheen).
  std::string ignored;
  for (const std::string& e : g.extensionsUsed) {
    const bool read = std::find(std::begin(kReadExtensions), std::end(kReadExtensions), e) !=
                      std::end(kReadExtensions);
    const bool warned = std::find(g.extensionsRequired.begin(), g.extensionsRequired.end(), e) !=
                        g.extensionsRequired.end();
    if (!read && !warned) ignored += (ignored.empty() ? "" : ", ") + e;
  }
  if (!ignored.empty()) {
    rad::warn(SourceLoc{path}, "the extensions " + ignored.substr(0, 400) +
                                   " are used but rad ignores them: materials take their base "
                                   "colour and emission alone, and reflect diffusely");
  }
  if (!g.skins.empty()) {
    rad::warn(SourceLoc{path}, std::to_string(g.skins.size()) +
                                   " skins ignored: skinned meshes are placed by their nodes, "
                                   "in the pose their vertices were written in");
  }
  if (!g.animations.empty()) {
    rad::warn(SourceLoc{path}, std::to_string(g.animations.size()) +
                                   " animations ignored: the scene is read as its nodes place "
                                   "it, unanimated");
  }
  // BLEND read as a cut-out: said once, for every material that asks for it.
  size_t blended = 0;
  std::string first_blended;
  for (size_t k = 0; k < g.materials.size(); ++k) {
    if (g.materials[k].alphaMode != "BLEND" || blended++ > 0) continue;
    first_blended = g.materials[k].name.empty() ? "material " + std::to_string(k)
                                                : "material '" + g.materials[k].name + "'";
  }
  if (blended > 0) {
    rad::warn(SourceLoc{path},
              first_blended +
                  (blended > 1 ? " (and " + std::to_string(blended - 1) + " more)" : "") + " has" +
                  " alphaMode BLEND, which rad cannot blend: it is read as MASK with "
                  "alphaCutoff 0.5, texels less than half opaque holes and the rest opaque");
  }

  Model m;
  m.path = path;
  std::vector<TextureCoordinates> coordinates(g.materials.size());
  for (size_t k = 0; k < g.materials.size(); ++k)
    m.materials.push_back(material_of(g.materials[k], c, g, path, m.textures, coordinates[k]));
  const uint32_t fallback = uint32_t(m.materials.size());
  bool fallback_used = false;
  size_t skipped = 0, total = 0;

  struct Item {
    int node, depth;
    glm::dmat4 parent;
  };
  std::vector<Item> stack;
  if (!g.scenes.empty()) {
    const int scene = g.defaultScene >= 0 ? g.defaultScene : 0;
    if (size_t(scene) >= g.scenes.size()) fail(path, "its default scene is not in its scenes");
    for (int root : g.scenes[size_t(scene)].nodes) stack.push_back({root, 0, glm::dmat4(1.0)});
  } else {
    // No scene (the spec leaves what to show to the reader): every node no other node holds,
    // as other readers place them.
    std::vector<bool> child(g.nodes.size(), false);
    for (const tinygltf::Node& n : g.nodes) {
      for (const int k : n.children) {
        if (k >= 0 && size_t(k) < child.size()) child[size_t(k)] = true;
      }
    }
    for (size_t i = child.size(); i-- > 0;) {
      if (!child[i]) stack.push_back({int(i), 0, glm::dmat4(1.0)});
    }
  }
  size_t meshes_placed = 0;
  size_t visits = 0;
  size_t uvless = 0;             // triangles of a textured material without its TEXCOORD_n
  uint32_t uvless_material = 0;  // the first's
  bool coloured = false;         // COLOR_0, which rad ignores
  bool range_warned = false;
  while (!stack.empty()) {
    const Item it = stack.back();
    stack.pop_back();
    if (++visits > kMaxPlacements) fail(path, "more than 10 million node placements (a cycle?)");
    if (it.node < 0 || size_t(it.node) >= g.nodes.size()) fail(path, "a scene names no such node");
    if (it.depth > kMaxDepth) fail(path, "nodes nested more than 256 deep (a cycle?)");
    const tinygltf::Node& n = g.nodes[size_t(it.node)];
    const glm::dmat4 world = it.parent * local_transform(n);
    for (int child : n.children) stack.push_back({child, it.depth + 1, world});
    const auto lights = n.extensions.find("KHR_lights_punctual");
    if (lights != n.extensions.end() && lights->second.IsObject() && lights->second.Has("light")) {
      const tinygltf::Value& k = lights->second.Get("light");
      const double index = k.IsNumber() ? k.GetNumberAsDouble() : -1.0;
      if (!(index >= 0.0 && index < double(g.lights.size()) && index == std::floor(index))) {
        fail(path, "node " + std::to_string(it.node) +
                       " names no such KHR_lights_punctual light (the file has " +
                       std::to_string(g.lights.size()) + ")");
      }
      m.lights.push_back(
          light_of(g.lights[size_t(index)], int(index), n.name, world, path, range_warned));
    }
    if (n.mesh < 0) continue;
    if (size_t(n.mesh) >= g.meshes.size()) fail(path, "a node names no such mesh");
    const tinygltf::Mesh& mesh = g.meshes[size_t(n.mesh)];
    ++meshes_placed;
    ModelGroup group;
    group.name = !n.name.empty()      ? n.name
                 : !mesh.name.empty() ? mesh.name
                                      : "node " + std::to_string(it.node);
    const bool mirrored = glm::determinant(world) < 0.0;
    for (const tinygltf::Primitive& p : mesh.primitives) {
      const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
      if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
          mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        ++skipped;
        continue;
      }
      const auto pos = p.attributes.find("POSITION");
      if (pos == p.attributes.end())
        fail(path, "a primitive of mesh '" + mesh.name + "' has no POSITION");
      const View positions = view(g, pos->second, path, "POSITION");
      if (positions.components != 3 || positions.component != TINYGLTF_COMPONENT_TYPE_FLOAT) {
        fail(path, "POSITION must be float VEC3");
      }
      std::vector<uint32_t> index;
      if (p.indices >= 0) {
        const View iv = view(g, p.indices, path, "indices");
        if (iv.components != 1 || iv.component == TINYGLTF_COMPONENT_TYPE_FLOAT)
          fail(path, "indices must be unsigned integers");
        index.reserve(iv.count);
        for (size_t i = 0; i < iv.count; ++i) {
          const double k = component(iv, i, 0);
          if (!(k < double(positions.count)))
            fail(path, "an index past the vertices of mesh '" + mesh.name + "'");
          index.push_back(uint32_t(k));
        }
      } else {
        for (size_t i = 0; i < positions.count; ++i) index.push_back(uint32_t(i));
      }
      auto corner = [&](uint32_t i) {
        const glm::dvec4 q =
            world * glm::dvec4(component(positions, i, 0), component(positions, i, 1),
                               component(positions, i, 2), 1.0);
        return Vec3(q);
      };
      const bool known = p.material >= 0 && size_t(p.material) < m.materials.size();
      fallback_used |= !known;
      const uint32_t material = known ? uint32_t(p.material) : fallback;
      // The base texture's coordinates, when the material has a texture and they are there.
      std::optional<View> uvs;
      const TextureCoordinates* uv_map = nullptr;
      if (known && m.materials[material].uses_coordinates()) {
        uv_map = &coordinates[material];
        const auto a = p.attributes.find("TEXCOORD_" + std::to_string(uv_map->set));
        if (a != p.attributes.end()) {
          uvs = view(g, a->second, path, "TEXCOORD");
          if (uvs->components != 2 || uvs->count < positions.count ||
              (uvs->component != TINYGLTF_COMPONENT_TYPE_FLOAT &&
               uvs->component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
               uvs->component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)) {
            fail(path, "TEXCOORD_" + std::to_string(uv_map->set) + " of mesh '" + mesh.name +
                           "' must be VEC2 (float, or normalized unsigned byte or short), one "
                           "per vertex");
          }
        }
      }
      coloured |= p.attributes.count("COLOR_0") > 0;
      if (uv_map && !uvs) {
        if (uvless == 0) uvless_material = material;
        uvless +=
            (mode == TINYGLTF_MODE_TRIANGLES ? index.size() / 3
                                             : index.size() - std::min<size_t>(index.size(), 2));
      }
      const double uv_unit = !uvs                                                       ? 1.0
                             : uvs->component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE  ? 255.0
                             : uvs->component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 65535.0
                                                                                        : 1.0;
      auto uv = [&](uint32_t i) {
        return uv_map->apply(component(*uvs, i, 0) / uv_unit, component(*uvs, i, 1) / uv_unit);
      };
      auto emit = [&](uint32_t a, uint32_t b, uint32_t d) {
        std::array<Vec3, 3> t{corner(a), corner(b), corner(d)};
        if (mirrored) std::swap(t[1], t[2]);  // a mirroring transform turns the front over
        for (const Vec3& v : t) {
          if (!glm::all(glm::lessThan(glm::abs(v), Vec3(3e38f))))
            fail(path, "a vertex is not finite after its transform");
        }
        if (uvs) {
          std::array<Vec2, 3> w{uv(a), uv(b), uv(d)};
          if (mirrored) std::swap(w[1], w[2]);
          // The group's coordinates are one per triangle or none.
          group.triangle_uvs.resize(group.triangles.size(), kNoTextureCoordinates);
          group.triangle_uvs.push_back(w);
        } else if (!group.triangle_uvs.empty()) {
          group.triangle_uvs.push_back(kNoTextureCoordinates);
        }
        group.triangles.push_back(t);
        group.material.push_back(material);
      };
      const size_t n3 = index.size();
      if (mode == TINYGLTF_MODE_TRIANGLES) {
        for (size_t i = 0; i + 2 < n3; i += 3) emit(index[i], index[i + 1], index[i + 2]);
      } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (size_t i = 0; i + 2 < n3; ++i) {
          if (i % 2 == 0)
            emit(index[i], index[i + 1], index[i + 2]);
          else
            emit(index[i + 1], index[i], index[i + 2]);
        }
      } else {
        for (size_t i = 1; i + 1 < n3; ++i) emit(index[0], index[i], index[i + 1]);
      }
      if ((total += group.triangles.size()) > kMaxTriangles) {
        fail(path, "more than 50 million triangles once its instances are placed");
      }
    }
    if (!group.triangles.empty()) m.groups.push_back(std::move(group));
  }
  if (fallback_used) m.materials.push_back(fallback_material("default", SourceLoc{path}));
  if (m.groups.empty()) {
    if (skipped > 0) {
      fail(path,
           "has no triangles, only points and lines, which reflect no light: export the "
           "model's surfaces");
    }
    fail(path, meshes_placed == 0 ? "has no triangles: its scene places no mesh"
                                  : "has no triangles: its meshes have no triangle primitives");
  }
  if (uvless > 0) {
    const ModelMaterial& first = m.materials[uvless_material];
    rad::warn(SourceLoc{path}, std::to_string(uvless) + " triangles of textured material '" +
                                   first.name +
                                   "' (the first) have no texture coordinates (TEXCOORD_" +
                                   std::to_string(coordinates[uvless_material].set) +
                                   "): they reflect the texture's mean colour" +
                                   (first.cutout ? " and are not cut out" : ""));
  }
  if (coloured) {
    rad::warn(SourceLoc{path},
              "the vertices' colours (COLOR_0) are ignored: triangles take their material's "
              "base colour");
  }
  if (skipped > 0) {
    rad::warn(SourceLoc{path}, std::to_string(skipped) +
                                   " primitives of points or lines skipped: only triangles "
                                   "reflect light");
  }
  return m;
}

Model read_gltf_file(const std::string& path, const SourceLoc& requested_at) {
  const std::string bytes = read_text_file(path, requested_at);
  const std::string folder = fs::path(path).parent_path().string();
  return parse_gltf(bytes, path, folder.empty() ? "." : folder);
}

}  // namespace rad
