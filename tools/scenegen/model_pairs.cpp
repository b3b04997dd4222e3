#include "scenegen/model_pairs.h"

#include <filesystem>
#include <fstream>
#include <utility>

#include "scene/texture.h"

namespace rad {

void add_quad(SceneDescription& s, const std::string& name, Vec3 a, Vec3 b, Vec3 c, Vec3 d,
              Vec3 reflectance, Vec3 emission, int k) {
  ObjectDescription o;
  o.name = name;
  o.kind = ObjectKind::Pure;
  o.material = {reflectance, emission};
  auto at = [&](float u, float v) {
    return a + (b - a) * u + (d - a) * v + (a - b + c - d) * (u * v);
  };
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) {
      const float u0 = float(i) / k, u1 = float(i + 1) / k, v0 = float(j) / k,
                  v1 = float(j + 1) / k;
      o.triangles.push_back({at(u0, v0), at(u1, v0), at(u1, v1)});
      o.triangles.push_back({at(u0, v0), at(u1, v1), at(u0, v1)});
    }
  }
  o.triangle_locs.resize(o.triangles.size());
  s.roots.push_back(int32_t(s.objects.size()));
  s.objects.push_back(std::move(o));
}

std::shared_ptr<TextureImage> checker_texture() {
  const unsigned char light[3] = {230, 60, 40}, dark[3] = {40, 160, 200};
  std::vector<unsigned char> p;
  for (int y = 0; y < kCheckerTexels; ++y) {
    for (int x = 0; x < kCheckerTexels; ++x) {
      const int i = x * kCheckerSquares / kCheckerTexels, j = y * kCheckerSquares / kCheckerTexels;
      const unsigned char* c = (i + j) % 2 == 0 ? light : dark;
      p.insert(p.end(), {c[0], c[1], c[2], 255});
    }
  }
  return texture_from_pixels(p.data(), kCheckerTexels, kCheckerTexels, "checker");
}

SceneDescription room_without_floor() {
  SceneDescription d;
  const Vec3 wall(0.6f), none(0.0f);
  add_quad(d, "ceiling", {0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, wall, none);
  add_quad(d, "lamp", {0.4f, 0.999f, 0.4f}, {0.6f, 0.999f, 0.4f}, {0.6f, 0.999f, 0.6f},
           {0.4f, 0.999f, 0.6f}, none, Vec3(20.0f));
  add_quad(d, "x0", {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, wall, none);
  add_quad(d, "x1", {1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}, wall, none);
  add_quad(d, "z0", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, wall, none);
  add_quad(d, "z1", {0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, wall, none);
  return d;
}

namespace {

// The floor's part x in [x0, x1], z in [z0, z1] at y = 0, facing up, as add_quad's corners.
void add_floor(SceneDescription& d, const std::string& name, float x0, float z0, float x1, float z1,
               Vec3 reflectance) {
  add_quad(d, name, {x0, 0, z0}, {x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0}, reflectance, Vec3(0.0f));
}

// Texture coordinates for each triangle of `o` from its corners.
template <typename Uv>
void set_uvs(ObjectDescription& o, Uv uv) {
  o.triangle_uvs.clear();
  for (const auto& t : o.triangles) o.triangle_uvs.push_back({uv(t[0]), uv(t[1]), uv(t[2])});
}

}  // namespace

SceneDescription checker_room(const std::shared_ptr<TextureImage>& checker, bool textured) {
  SceneDescription d = room_without_floor();
  if (textured) {
    add_floor(d, "floor", 0, 0, 1, 1, checker->mean);  // Kd 1 times the texture's mean
    ObjectDescription& o = d.objects.back();
    // The floor cut into squares has sharp edges and nothing beyond its own: texels shown as
    // squares (NEAREST), the image clamped at the floor's edges rather than repeated.
    o.base_texture.image = checker;
    o.base_texture.sampler.nearest = true;
    o.base_texture.sampler.wrap_s = o.base_texture.sampler.wrap_t = TextureWrap::ClampToEdge;
    set_uvs(o, [](const Vec3& p) { return Vec2(p.x, p.z); });
    return d;
  }
  const TextureImage::Level& l = checker->levels.front();
  const int texels = l.width / kCheckerSquares;
  const float s = 1.0f / kCheckerSquares;
  for (int i = 0; i < kCheckerSquares; ++i) {
    for (int j = 0; j < kCheckerSquares; ++j) {
      // The square's colour as decoded: a texel inside it.
      const int x = i * texels + texels / 2, y = j * texels + texels / 2;
      const Vec4 c = l.texels[size_t(y) * size_t(l.width) + size_t(x)];
      add_floor(d, "floor " + std::to_string(i) + " " + std::to_string(j), float(i) * s,
                float(j) * s, float(i + 1) * s, float(j + 1) * s, Vec3(c));
    }
  }
  return d;
}

SceneDescription checker_lit_room(const std::shared_ptr<TextureImage>& checker, bool textured) {
  SceneDescription d = checker_room(checker, textured);
  for (ObjectDescription& o : d.objects) {
    if (o.name == "lamp") o.material.emission = Vec3(0.0f);
    if (o.name.rfind("floor", 0) != 0) continue;
    o.material.emission = o.material.reflectance;
    o.material.reflectance = Vec3(0.0f);
    if (textured) o.emissive_texture = std::exchange(o.base_texture, {});
  }
  return d;
}

SceneDescription cutout_room(bool cut) {
  SceneDescription d = room_without_floor();
  add_floor(d, "floor", 0, 0, 1, 1, Vec3(0.6f));
  const float right = cut ? 0.8f : 0.5f;
  add_quad(d, "leaf", {0.2f, 0.5f, 0.2f}, {0.2f, 0.5f, 0.8f}, {right, 0.5f, 0.8f},
           {right, 0.5f, 0.2f}, Vec3(0.5f, 0.7f, 0.3f), Vec3(0.0f));
  if (!cut) return d;
  auto image = std::make_shared<TextureImage>();
  image->name = "half";
  image->has_alpha = true;
  TextureImage::Level l;
  l.width = l.height = 64;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) l.texels.push_back(Vec4(1.0f, 1.0f, 1.0f, x < 32 ? 1.0f : 0.0f));
  }
  image->levels.push_back(l);
  image->mean = Vec3(1.0f);
  ObjectDescription& leaf = d.objects.back();
  leaf.cutout.texture.image = image;
  leaf.cutout.texture.sampler.wrap_s = leaf.cutout.texture.sampler.wrap_t =
      TextureWrap::ClampToEdge;
  set_uvs(leaf, [](const Vec3& p) { return Vec2((p.x - 0.2f) / 0.6f, (p.z - 0.2f) / 0.6f); });
  return d;
}

std::string screen_room(const std::string& screen) {
  auto quad = [](const std::string& name, const std::string& corners, const std::string& material) {
    return "Object \"" + name + "\" Pure {\n" + material + "\nData {\n" + corners + "}\n}\n";
  };
  const std::string wall = "Reflectivity 0.7 Color <1 1 1> Emission 0";
  std::string s = "\"screen room\"\nObject \"room\" Assembly {\n";
  s += quad("floor", "<0 0 0> <0 0 1> <2 0 1>\n<0 0 0> <2 0 1> <2 0 0>\n", wall);
  s += quad("ceiling", "<0 1 0> <2 1 0> <2 1 1>\n<0 1 0> <2 1 1> <0 1 1>\n", wall);
  s += quad("x0", "<0 0 0> <0 1 0> <0 1 1>\n<0 0 0> <0 1 1> <0 0 1>\n", wall);
  s += quad("x2", "<2 0 0> <2 0 1> <2 1 1>\n<2 0 0> <2 1 1> <2 1 0>\n", wall);
  s += quad("z0", "<0 0 0> <2 0 0> <2 1 0>\n<0 0 0> <2 1 0> <0 1 0>\n", wall);
  s += quad("z1", "<0 0 1> <0 1 1> <2 1 1>\n<0 0 1> <2 1 1> <2 0 1>\n", wall);
  s += quad("lamp",
            "<0.4 0.999 0.4> <0.6 0.999 0.4> <0.6 0.999 0.6>\n"
            "<0.4 0.999 0.4> <0.6 0.999 0.6> <0.4 0.999 0.6>\n",
            "Reflectivity 0 Color <1 1 1> Emission 30");
  return s + screen + "}\n";
}

std::string screen_object(const std::string& name, const std::string& flags, bool turned) {
  const char* facing = "<1 0 0.1> <1 0 0.9> <1 0.6 0.9>\n<1 0 0.1> <1 0.6 0.9> <1 0.6 0.1>\n";
  const char* away = "<1 0 0.1> <1 0.6 0.9> <1 0 0.9>\n<1 0 0.1> <1 0.6 0.1> <1 0.6 0.9>\n";
  return "Object \"" + name + "\" Pure " + flags +
         " {\nReflectivity 0.5 Color <1 0.8 0.6> Emission 0\nData {\n" + (turned ? away : facing) +
         "}\n}\n";
}

void write_obj_soup(const Hierarchy& h, const std::string& obj_path) {
  const std::filesystem::path mtl_path = std::filesystem::path(obj_path).replace_extension(".mtl");
  std::ofstream out(obj_path), mtl(mtl_path);
  out << "mtllib " << mtl_path.filename().string() << "\n";
  out.precision(9);
  mtl.precision(9);
  size_t v = 0;
  for (size_t i = 0; i < h.objects.size(); ++i) {
    const SceneObject& o = h.objects[i];
    if (o.kind != ObjectKind::Pure) continue;
    const Vec3 rho = o.material.reflectance, e = o.material.emission;
    mtl << "newmtl m" << i << "\nKd " << rho.x << ' ' << rho.y << ' ' << rho.z << "\nKe " << e.x
        << ' ' << e.y << ' ' << e.z << "\n";
    out << "o pure" << i << "\nusemtl m" << i << "\n";
    for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t) {
      for (const Vec3& p : h.triangles.corners[t])
        out << "v " << p.x << ' ' << p.y << ' ' << p.z << "\n";
      out << "f " << v + 1 << ' ' << v + 2 << ' ' << v + 3 << "\n";
      v += 3;
    }
  }
}

}  // namespace rad
