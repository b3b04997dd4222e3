#include "reference/ply_reader.h"

#include <fmt/format.h>

#include <bit>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace rad {

namespace {

enum class Type { I8, U8, I16, U16, I32, U32, F32, F64 };

Type parse_type(const std::string& s, const std::string& path) {
  if (s == "char" || s == "int8") return Type::I8;
  if (s == "uchar" || s == "uint8") return Type::U8;
  if (s == "short" || s == "int16") return Type::I16;
  if (s == "ushort" || s == "uint16") return Type::U16;
  if (s == "int" || s == "int32") return Type::I32;
  if (s == "uint" || s == "uint32") return Type::U32;
  if (s == "float" || s == "float32") return Type::F32;
  if (s == "double" || s == "float64") return Type::F64;
  throw Error(SourceLoc{path, 0, 0}, fmt::format("unknown PLY type '{}'", s));
}

struct Property {
  std::string name;
  Type type = Type::F32;
  bool list = false;
  Type count_type = Type::U8;
};

struct Element {
  std::string name;
  size_t count = 0;
  std::vector<Property> properties;
};

template <typename T>
double get(std::istream& in) {
  static_assert(std::endian::native == std::endian::little, "PLY reader assumes little-endian");
  char b[sizeof(T)];
  in.read(b, sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return double(v);
}

double read_value(std::istream& in, Type t, bool ascii) {
  if (ascii) {
    double v;
    in >> v;
    return v;
  }
  switch (t) {
    case Type::I8:
      return get<int8_t>(in);
    case Type::U8:
      return get<uint8_t>(in);
    case Type::I16:
      return get<int16_t>(in);
    case Type::U16:
      return get<uint16_t>(in);
    case Type::I32:
      return get<int32_t>(in);
    case Type::U32:
      return get<uint32_t>(in);
    case Type::F32:
      return get<float>(in);
    case Type::F64:
      return get<double>(in);
  }
  return 0.0;
}

}  // namespace

PlyMesh read_radiosity_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const SourceLoc where{path, 0, 0};
  if (!in) throw Error(where, "cannot read the PLY file");
  std::string line;
  std::getline(in, line);
  if (line != "ply") throw Error(where, "not a PLY file");
  bool ascii = false;
  std::vector<Element> elements;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "format") {
      std::string format;
      words >> format;
      if (format == "ascii") {
        ascii = true;
      } else if (format != "binary_little_endian") {
        throw Error(where, fmt::format("unsupported PLY format '{}'", format));
      }
    } else if (key == "element") {
      Element e;
      words >> e.name >> e.count;
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) throw Error(where, "property before any element");
      Property p;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        p.list = true;
        p.count_type = parse_type(count_type, path);
        p.type = parse_type(item_type, path);
      } else {
        p.type = parse_type(type, path);
      }
      words >> p.name;
      elements.back().properties.push_back(p);
    } else if (key == "end_header") {
      break;
    }
  }

  PlyMesh mesh;
  for (const Element& e : elements) {
    for (size_t i = 0; i < e.count; ++i) {
      double xyz[3] = {0, 0, 0}, rgb[3] = {0, 0, 0};
      for (const Property& p : e.properties) {
        if (p.list) {
          const size_t n = size_t(read_value(in, p.count_type, ascii));
          if (e.name == "face" && p.name == "vertex_indices" && n != 3) {
            throw Error(where, fmt::format("face {} has {} vertices; rad writes triangles", i, n));
          }
          for (size_t k = 0; k < n; ++k) {
            const double v = read_value(in, p.type, ascii);
            if (e.name == "face" && p.name == "vertex_indices") mesh.indices.push_back(uint32_t(v));
          }
          continue;
        }
        const double v = read_value(in, p.type, ascii);
        if (e.name != "vertex") continue;
        if (p.name == "x") xyz[0] = v;
        if (p.name == "y") xyz[1] = v;
        if (p.name == "z") xyz[2] = v;
        if (p.name == "radiosity_r") rgb[0] = v;
        if (p.name == "radiosity_g") rgb[1] = v;
        if (p.name == "radiosity_b") rgb[2] = v;
      }
      if (!in) throw Error(where, fmt::format("truncated in element '{}'", e.name));
      if (e.name == "vertex") {
        mesh.position.emplace_back(float(xyz[0]), float(xyz[1]), float(xyz[2]));
        mesh.radiosity.emplace_back(float(rgb[0]), float(rgb[1]), float(rgb[2]));
      }
    }
  }
  for (uint32_t i : mesh.indices) {
    if (i >= mesh.position.size()) throw Error(where, "face index out of range");
  }
  return mesh;
}

}  // namespace rad
