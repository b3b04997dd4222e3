#include "scene/ply_reader.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <sstream>

#include "scene/text_file.h"

namespace rad {

namespace {

enum class Type : uint8_t { I8, U8, I16, U16, I32, U32, F32, F64 };

std::optional<Type> parse_type(const std::string& s) {
  if (s == "char" || s == "int8") return Type::I8;
  if (s == "uchar" || s == "uint8") return Type::U8;
  if (s == "short" || s == "int16") return Type::I16;
  if (s == "ushort" || s == "uint16") return Type::U16;
  if (s == "int" || s == "int32") return Type::I32;
  if (s == "uint" || s == "uint32") return Type::U32;
  if (s == "float" || s == "float32") return Type::F32;
  if (s == "double" || s == "float64") return Type::F64;
  return std::nullopt;
}

size_t size_of(Type t) {
  switch (t) {
    case Type::I8:
    case Type::U8:
      return 1;
    case Type::I16:
    case Type::U16:
      return 2;
    case Type::I32:
    case Type::U32:
    case Type::F32:
      return 4;
    case Type::F64:
      return 8;
  }
  return 1;
}

struct Property {
  std::string name;
  Type type = Type::F32;
  bool list = false;
  Type count_type = Type::U8;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
};

enum class Format { Ascii, Little, Big };

// Values of the body, one at a time, from text or binary.
// The value of type T whose bytes (in this machine's order) start at `raw`.
template <typename T>
double as(const unsigned char* raw) {
  T v;
  std::memcpy(&v, raw, sizeof v);
  return double(v);
}

class Body {
 public:
  Body(std::string_view bytes, size_t at, Format f, const std::string& path, int line)
      : b_(bytes), at_(at), format_(f), path_(path), line_(line) {}

  double value(Type t) {
    if (format_ == Format::Ascii) return ascii();
    const size_t n = size_of(t);
    if (at_ + n > b_.size()) fail("the file ends inside its data");
    unsigned char raw[8];
    std::memcpy(raw, b_.data() + at_, n);
    at_ += n;
    const bool swap = (format_ == Format::Big) == (std::endian::native == std::endian::little);
    if (swap) std::reverse(raw, raw + n);
    switch (t) {
      case Type::I8:
        return as<int8_t>(raw);
      case Type::U8:
        return as<uint8_t>(raw);
      case Type::I16:
        return as<int16_t>(raw);
      case Type::U16:
        return as<uint16_t>(raw);
      case Type::I32:
        return as<int32_t>(raw);
      case Type::U32:
        return as<uint32_t>(raw);
      case Type::F32:
        return as<float>(raw);
      case Type::F64:
        return as<double>(raw);
    }
    return 0.0;
  }
  // Bytes (binary) or characters (ASCII) left: a count may not claim more items than this.
  size_t left() const { return b_.size() - at_; }
  [[noreturn]] void fail(const std::string& why) const {
    throw Error(SourceLoc{path_, format_ == Format::Ascii ? line_ : 0, 0}, why);
  }

 private:
  double ascii() {
    while (at_ < b_.size() && std::isspace(static_cast<unsigned char>(b_[at_]))) {
      if (b_[at_] == '\n') ++line_;
      ++at_;
    }
    size_t end = at_;
    while (end < b_.size() && !std::isspace(static_cast<unsigned char>(b_[end]))) ++end;
    if (end == at_) fail("the file ends inside its data");
    double v = 0.0;
    const auto r = std::from_chars(b_.data() + at_, b_.data() + end, v);
    if (r.ec != std::errc() || r.ptr != b_.data() + end) {
      fail("'" + std::string(b_.substr(at_, std::min<size_t>(end - at_, 40))) +
           "' is not a number");
    }
    at_ = end;
    return v;
  }

  std::string_view b_;
  size_t at_;
  Format format_;
  const std::string& path_;
  int line_;
};

}  // namespace

PlyData parse_ply_data(std::string_view bytes, const std::string& path) {
  // Header: text lines up to "end_header".
  const size_t end = bytes.find("end_header");
  if (bytes.substr(0, 3) != "ply" || end == std::string_view::npos) {
    throw Error(SourceLoc{path, 1, 1}, "not a PLY file (no 'ply' ... 'end_header' header)");
  }
  size_t body = bytes.find('\n', end);
  body = body == std::string_view::npos ? bytes.size() : body + 1;
  std::istringstream header{std::string(bytes.substr(0, end))};
  std::optional<Format> format;
  std::vector<Element> elements;
  std::string line;
  int number = 0;
  for (; std::getline(header, line); ++number) {
    std::istringstream words(line);
    std::string word;
    words >> word;
    const SourceLoc loc{path, number + 1, 1};
    // obj_info lines are the PLY standard's, and carry nothing rad reads.
    if (word.empty() || word == "ply" || word == "comment" || word == "obj_info") continue;
    if (word == "format") {
      std::string f;
      words >> f;
      if (f == "ascii")
        format = Format::Ascii;
      else if (f == "binary_little_endian")
        format = Format::Little;
      else if (f == "binary_big_endian")
        format = Format::Big;
      else
        throw Error(loc, "unknown PLY format '" + f + "'");
    } else if (word == "element") {
      Element e;
      if (!(words >> e.name >> e.count)) throw Error(loc, "expected 'element NAME COUNT'");
      elements.push_back(std::move(e));
    } else if (word == "property") {
      if (elements.empty()) throw Error(loc, "a property before any element");
      Property p;
      std::string t;
      words >> t;
      if (t == "list") {
        std::string ct, vt;
        words >> ct >> vt >> p.name;
        const auto c = parse_type(ct), v = parse_type(vt);
        if (!c || !v || *c == Type::F32 || *c == Type::F64)
          throw Error(loc, "bad list property types");
        p.list = true, p.count_type = *c, p.type = *v;
      } else {
        const auto v = parse_type(t);
        if (!v) throw Error(loc, "unknown property type '" + t + "'");
        p.type = *v;
        words >> p.name;
      }
      elements.back().properties.push_back(std::move(p));
    } else if (elements.empty()) {
      // Free text before the first element (Blender 2.4's "Created by Blender3D ...", written
      // without `comment`) cannot change what the data means: other readers skip it, so does rad.
      warn(loc, "header line '" + line.substr(0, 60) +
                    "' skipped: not a PLY keyword (a credit line should start with 'comment')");
    } else {
      // Among the elements, an unknown line may be a misspelt element or property: skipping it
      // would read the data as something else.
      throw Error(loc, "unknown header line '" + word +
                           "': expected element, property or comment (PLY keywords)");
    }
  }
  if (!format) throw Error(SourceLoc{path, 1, 1}, "no 'format' line");

  PlyData out;
  // The header's lines, then end_header's: the data starts on the line after.
  Body in(bytes, body, *format, path, number + 2);
  bool seen_vertex = false, seen_face = false;
  for (const Element& e : elements) {
    // Each item takes at least one byte (binary) or two characters (ASCII) per property.
    const size_t least =
        std::max<size_t>(e.properties.size(), 1) * (*format == Format::Ascii ? 2 : 1);
    if (e.count > in.left() / least) {
      in.fail("element '" + e.name + "' claims " + std::to_string(e.count) +
              " items, more than the file holds");
    }
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    // One element of each: a second "vertex" element would leave the columns of the first
    // shorter than the count the faces are checked against (fuzzing found it).
    if ((is_vertex && seen_vertex) || (is_face && seen_face))
      in.fail("a second '" + e.name + "' element");
    seen_vertex |= is_vertex, seen_face |= is_face;
    std::vector<std::vector<float>*> columns;
    for (const Property& prop : e.properties) {
      columns.push_back(is_vertex && !prop.list ? &out.vertex[prop.name] : nullptr);
    }
    if (is_vertex) out.vertex_count = size_t(e.count);
    if (is_face && out.face_first.empty()) out.face_first.push_back(0);
    for (uint64_t i = 0; i < e.count; ++i) {
      for (size_t k = 0; k < e.properties.size(); ++k) {
        const Property& prop = e.properties[k];
        if (!prop.list) {
          const double v = in.value(prop.type);
          if (columns[k]) {
            // Only positions must be finite: a NaN normal or splat size (scanners write them)
            // is never read by the solve.
            const bool position = prop.name == "x" || prop.name == "y" || prop.name == "z";
            if (position && (!std::isfinite(v) || std::abs(v) > 3e38)) {
              in.fail("vertex " + std::to_string(i) + ": its " + prop.name + " is not finite");
            }
            // (A double beyond float's range has no float value: NaN stands for it.)
            const bool fits = std::isfinite(v) && std::abs(v) <= 3e38;
            columns[k]->push_back(fits ? float(v) : std::numeric_limits<float>::quiet_NaN());
          }
          continue;
        }
        const double count = in.value(prop.count_type);
        if (!(count >= 0) || count != std::floor(count)) {
          in.fail("element '" + e.name + "' item " + std::to_string(i) + ": list '" + prop.name +
                  "' has a length of " + std::to_string(count) +
                  ", not a whole number (do the header's properties match the data?)");
        }
        if (count > double(in.left())) in.fail("a list longer than the file");
        const bool indices =
            is_face && (prop.name == "vertex_indices" || prop.name == "vertex_index");
        for (size_t n = size_t(count); n > 0; --n) {
          const double v = in.value(prop.type);
          if (!indices) continue;
          if (!(v >= 0) || v >= double(out.vertex_count) || v != std::floor(v)) {
            in.fail("face " + std::to_string(i) + " names vertex " + std::to_string(v) + " of " +
                    std::to_string(out.vertex_count));
          }
          out.face_indices.push_back(uint32_t(v));
        }
        if (indices) out.face_first.push_back(uint32_t(out.face_indices.size()));
      }
    }
    if (is_vertex && !out.face_first.empty()) in.fail("the face element comes before the vertices");
  }
  return out;
}

const std::vector<float>& PlyData::column(const std::string& name, const std::string& path) const {
  const auto it = vertex.find(name);
  if (it == vertex.end())
    throw Error(SourceLoc{path}, "the vertices have no property '" + name + "'");
  return it->second;
}

Model parse_ply(std::string_view bytes, const std::string& path) {
  const PlyData d = parse_ply_data(bytes, path);
  const std::vector<float>&x = d.column("x", path), &y = d.column("y", path),
        &z = d.column("z", path);
  for (const std::vector<float>* c : {&x, &y, &z}) {
    if (c->size() != d.vertex_count)
      throw Error(SourceLoc{path}, "the vertices' x, y and z are not one each per vertex");
  }
  const auto corner = [&](uint32_t i) { return Vec3(x[i], y[i], z[i]); };
  Model m;
  m.path = path;
  const std::string stem = std::filesystem::path(path).stem().string();
  m.materials.push_back(fallback_material(stem, SourceLoc{path}));
  ModelGroup g;
  g.name = stem;
  for (size_t f = 0; f + 1 < d.face_first.size(); ++f) {
    const uint32_t* v = d.face_indices.data() + d.face_first[f];
    for (uint32_t k = 2; k < d.face_first[f + 1] - d.face_first[f]; ++k) {
      g.triangles.push_back({corner(v[0]), corner(v[k - 1]), corner(v[k])});
      g.material.push_back(0);
    }
  }
  if (g.triangles.empty()) {
    throw Error(SourceLoc{path}, d.face_first.empty()
                                     ? "has no faces (" + std::to_string(d.vertex_count) +
                                           " vertices and no 'face' element): a point cloud "
                                           "has no surface to light"
                                     : "has no faces of three or more vertices");
  }
  m.groups.push_back(std::move(g));
  for (const char* colour : {"red", "diffuse_red", "r"}) {
    if (!d.vertex.contains(colour)) continue;
    warn(SourceLoc{path}, std::string("the vertices' colours (") + colour +
                              ", ...) are ignored: the model reflects one grey, 0.8");
    break;
  }
  return m;
}

Model read_ply_file(const std::string& path, const SourceLoc& requested_at) {
  return parse_ply(read_text_file(path, requested_at), path);
}

}  // namespace rad
