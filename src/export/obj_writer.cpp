#include "export/obj_writer.h"

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <iterator>
#include <memory>
#include <vector>

#include "core/atomic_file.h"
#include "export/texture_png.h"

namespace rad {

void write_obj(std::ostream& out, const OutputMesh& m, const ToneMap& tm,
               const std::string& mtl_file) {
  const bool uv = !m.uv().empty() && !mtl_file.empty();
  fmt::memory_buffer b;
  auto it = std::back_inserter(b);
  fmt::format_to(it,
                 "# rad radiosity: {} vertices, {} faces; v x y z r g b, rgb = display "
                 "colour (sRGB) in 0-1\n",
                 m.position().size(), m.face_count());
  if (uv) fmt::format_to(it, "mtllib {}\n", mtl_file);
  for (size_t v = 0; v < m.position().size(); ++v) {
    uint8_t c[3];
    to_srgb8(m.display[v], tm, c);
    const Vec3& p = m.position()[v];
    fmt::format_to(it, "v {} {} {} {} {} {}\n", p.x, p.y, p.z, float(c[0]) / 255.0f,
                   float(c[1]) / 255.0f, float(c[2]) / 255.0f);
  }
  if (!uv) {
    for (size_t f = 0; f < m.face_count(); ++f) {
      const uint32_t* i = &m.indices()[3 * f];
      fmt::format_to(it, "f {} {} {}\n", i[0] + 1, i[1] + 1, i[2] + 1);
    }
    out.write(b.data(), std::streamsize(b.size()));
    return;
  }
  for (const Vec2& t : m.uv()) fmt::format_to(it, "vt {} {}\n", t.x, 1.0f - t.y);
  const std::vector<int32_t>& texture = m.face_texture();
  const int32_t textures = int32_t(m.textures().size());
  for (int32_t k = -1; k < textures; ++k) {
    bool named = false;
    for (size_t f = 0; f < m.face_count(); ++f) {
      if ((texture.empty() ? -1 : texture[f]) != k) continue;
      if (!named) {
        fmt::format_to(it, "usemtl {}\n",
                       k < 0 ? std::string("radiosity") : fmt::format("texture{}", k));
        named = true;
      }
      const uint32_t* i = &m.indices()[3 * f];
      fmt::format_to(it, "f {0}/{0} {1}/{1} {2}/{2}\n", i[0] + 1, i[1] + 1, i[2] + 1);
    }
  }
  out.write(b.data(), std::streamsize(b.size()));
}

std::string write_obj_materials(const std::string& obj_path, const OutputMesh& mesh,
                                const WriteBeside& write_beside) {
  if (mesh.uv().empty()) return {};
  namespace fs = std::filesystem;
  const fs::path obj(obj_path);
  const std::string stem = obj.stem().string();
  const std::string mtl_name = stem + ".mtl";
  // Without a caller's staging, every file is held under its temporary name until all are
  // written, so a failure leaves none of them.
  std::vector<std::unique_ptr<AtomicFile>> held;
  auto write_file = [&](const std::string& name, const std::string& bytes) {
    const std::string path = (obj.parent_path() / name).string();
    auto write = [&](const std::string& to) {
      AtomicFile f(to);
      f.stream().write(bytes.data(), std::streamsize(bytes.size()));
      f.commit();
    };
    if (write_beside) {
      write_beside(path, write);
    } else {
      held.push_back(std::make_unique<AtomicFile>(path));
      held.back()->stream().write(bytes.data(), std::streamsize(bytes.size()));
    }
  };
  std::vector<const TextureImage*> written;
  std::vector<std::string> file_of;  // per entry of `written`
  fmt::memory_buffer b;
  auto it = std::back_inserter(b);
  fmt::format_to(it,
                 "# materials of {}, written by rad: the light is in the vertex colours of the "
                 "OBJ (the texture filtered in); map_Kd is the texture alone\n"
                 "newmtl radiosity\nKd 1 1 1\nillum 0\n",
                 obj.filename().string());
  const std::vector<OutputTexture>& textures = mesh.textures();
  for (size_t k = 0; k < textures.size(); ++k) {
    const TextureMap& t = textures[k].map;
    size_t i = 0;
    while (i < written.size() && written[i] != t.image.get()) ++i;
    if (i == written.size()) {
      written.push_back(t.image.get());
      file_of.push_back(fmt::format("{}_texture{}.png", stem, k));
      write_file(file_of.back(), encode_png(*t.image));
    }
    // OBJ can say clamp (both directions) or repeat; a mirrored repeat reads as repeat.
    const bool clamp = t.sampler.wrap_s == TextureWrap::ClampToEdge &&
                       t.sampler.wrap_t == TextureWrap::ClampToEdge;
    fmt::format_to(it, "newmtl texture{}\nKd 1 1 1\nillum 0\nmap_Kd {}{}\n", k,
                   clamp ? "-clamp on " : "", file_of[i]);
  }
  write_file(mtl_name, std::string(b.data(), b.size()));
  for (auto& f : held) f->commit();
  return mtl_name;
}

}  // namespace rad
