#include "scene/off_reader.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "scene/text_file.h"
#include "scene/tokenizer.h"

namespace rad {

namespace {

struct Field {
  std::string_view text;
  int column = 0;
};

struct Line {
  int number = 0;
  std::vector<Field> fields;
};

// Splits the text into its non-empty lines of whitespace-separated fields, '#' comments removed.
std::vector<Line> split_lines(std::string_view text, int& end_line, int& end_column) {
  std::vector<Line> lines;
  size_t pos = 0;
  int number = 1;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") pos = 3;  // a UTF-8 byte-order mark
  size_t line_start = pos;
  while (pos <= text.size()) {
    size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view body = text.substr(pos, eol - pos);
    size_t hash = body.find('#');
    if (hash != std::string_view::npos) body = body.substr(0, hash);
    Line line{number, {}};
    size_t i = 0;
    while (i < body.size()) {
      while (i < body.size() && std::isspace(static_cast<unsigned char>(body[i]))) ++i;
      size_t start = i;
      while (i < body.size() && !std::isspace(static_cast<unsigned char>(body[i]))) ++i;
      if (i > start) {
        int column = static_cast<int>(pos + start - line_start) + 1;
        line.fields.push_back({body.substr(start, i - start), column});
      }
    }
    if (!line.fields.empty()) lines.push_back(std::move(line));
    if (eol == text.size()) {
      end_line = number;
      end_column = static_cast<int>(eol - line_start) + 1;
      break;
    }
    pos = eol + 1;
    line_start = pos;
    ++number;
  }
  return lines;
}

class OffParser {
 public:
  OffParser(std::string_view text, const std::string& path) : path_(path) {
    lines_ = split_lines(text, end_line_, end_column_);
  }

  OffTriangles parse() {
    OffTriangles out;
    size_t first_count_field = read_header();
    long long counts[3] = {0, 0, 0};
    const Line& count_line = next_line("the vertex and face counts");
    if (count_line.fields.size() < first_count_field + 2) {
      const Field& f = count_line.fields.back();
      fail(count_line, f,
           "expected the vertex and face counts but found only '" + std::string(f.text) + "'");
    }
    for (size_t k = 0; k < 3 && first_count_field + k < count_line.fields.size(); ++k) {
      const Field& f = count_line.fields[first_count_field + k];
      if (!parse_integer(f.text, counts[k]) || counts[k] < 0) {
        fail(count_line, f,
             "expected a count (a non-negative integer) but found '" + std::string(f.text) + "'");
      }
    }
    const Field& face_count_field = count_line.fields[first_count_field + 1];
    if (counts[1] == 0) fail(count_line, face_count_field, "OFF file has no faces");

    out.vertex_count = static_cast<size_t>(counts[0]);
    out.face_count = static_cast<size_t>(counts[1]);
    std::vector<Vec3> vertices;
    vertices.reserve(std::min(out.vertex_count, lines_.size()));
    for (size_t v = 0; v < out.vertex_count; ++v) {
      const Line& line =
          next_line("vertex " + std::to_string(v) + " of " + std::to_string(out.vertex_count));
      Vec3 p;
      for (int k = 0; k < 3; ++k) {
        if (static_cast<size_t>(k) >= line.fields.size()) {
          fail(line, line.fields.back(),
               "expected 3 vertex coordinates but found " + std::to_string(line.fields.size()));
        }
        const Field& f = line.fields[k];
        NumberParse n = parse_number(f.text);
        if (n.status == NumberParse::NotANumber) {
          fail(line, f, "expected a vertex coordinate but found '" + std::string(f.text) + "'");
        }
        if (n.status == NumberParse::NonFinite) {
          fail(line, f, "non-finite number '" + std::string(f.text) + "'");
        }
        p[k] = static_cast<float>(n.value);
      }
      // Whatever follows x y z (normal, colour, texture coordinates) is ignored.
      vertices.push_back(p);
    }
    for (size_t face = 0; face < out.face_count; ++face) {
      const Line& line =
          next_line("face " + std::to_string(face) + " of " + std::to_string(out.face_count));
      SourceLoc loc{path_, line.number, line.fields[0].column};
      long long n = 0;
      if (!parse_integer(line.fields[0].text, n)) {
        fail(line, line.fields[0],
             "expected a face's vertex count but found '" + std::string(line.fields[0].text) + "'");
      }
      if (n < 3) {
        fail(line, line.fields[0],
             "a face needs at least 3 vertices but this one has " + std::to_string(n));
      }
      if (line.fields.size() < static_cast<size_t>(n) + 1) {
        fail(line, line.fields.back(),
             "face has " + std::to_string(n) + " vertices but only " +
                 std::to_string(line.fields.size() - 1) + " indices");
      }
      std::vector<int64_t> index(static_cast<size_t>(n));
      for (long long k = 0; k < n; ++k) {
        const Field& f = line.fields[static_cast<size_t>(k) + 1];
        long long i = 0;
        if (!parse_integer(f.text, i)) {
          fail(line, f, "expected a vertex index but found '" + std::string(f.text) + "'");
        }
        if (i < 0 || i >= static_cast<long long>(vertices.size())) {
          fail(line, f,
               "vertex index " + std::string(f.text) + " out of range [0, " +
                   std::to_string(vertices.size()) + ")");
        }
        index[static_cast<size_t>(k)] = i;
      }
      // Any colour after the indices is ignored.
      for (size_t k = 1; k + 1 < index.size(); ++k) {
        out.triangles.push_back({vertices[index[0]], vertices[index[k]], vertices[index[k + 1]]});
        out.triangle_locs.push_back(loc);
      }
    }
    return out;
  }

 private:
  // Consumes the header keyword if present; returns the index of the first count field on the
  // line that holds the counts (the header's own line when the counts follow it there).
  size_t read_header() {
    if (lines_.empty()) {
      throw Error(SourceLoc{path_, end_line_, end_column_},
                  "unexpected end of file: expected an OFF header or the vertex and face counts");
    }
    const Line& first = lines_[0];
    const Field& f = first.fields[0];
    long long ignored = 0;
    if (parse_integer(f.text, ignored)) return 0;  // no header keyword
    std::string_view word = f.text;
    if (word.size() < 3 || word.substr(word.size() - 3) != "OFF") {
      fail(first, f,
           "expected an OFF header or the vertex and face counts but found '" + std::string(word) +
               "'");
    }
    std::string_view prefix = word.substr(0, word.size() - 3);
    bool st = false, c = false, n = false;
    while (!prefix.empty()) {
      if (prefix.substr(0, 2) == "ST" && !st) {
        st = true;
        prefix.remove_prefix(2);
      } else if (prefix[0] == 'C' && !c) {
        c = true;
        prefix.remove_prefix(1);
      } else if (prefix[0] == 'N' && !n) {
        n = true;
        prefix.remove_prefix(1);
      } else if (prefix[0] == '4' || prefix[0] == 'n') {
        fail(first, f,
             "unsupported OFF variant '" + std::string(word) +
                 "' (only 3D OFF, with optional ST, C and N, is read)");
      } else {
        fail(first, f, "unknown OFF header '" + std::string(word) + "'");
      }
    }
    if (first.fields.size() > 1 && first.fields[1].text == "BINARY") {
      fail(first, first.fields[1], "binary OFF files are not supported");
    }
    if (first.fields.size() > 1) {
      next_ = 0;  // the counts follow the keyword on the same line
      return 1;
    }
    next_ = 1;
    return 0;
  }

  const Line& next_line(const std::string& what) {
    if (next_ >= lines_.size()) {
      throw Error(SourceLoc{path_, end_line_, end_column_},
                  "unexpected end of file: expected " + what);
    }
    return lines_[next_++];
  }

  [[noreturn]] void fail(const Line& line, const Field& field, const std::string& message) {
    throw Error(SourceLoc{path_, line.number, field.column}, message);
  }

  std::string path_;
  std::vector<Line> lines_;
  size_t next_ = 0;
  int end_line_ = 1;
  int end_column_ = 1;
};

}  // namespace

OffTriangles parse_off_text(std::string_view text, const std::string& path) {
  return OffParser(text, path).parse();
}

OffTriangles read_off_file(const std::string& path, const SourceLoc& requested_at) {
  std::string text = read_text_file(path, requested_at);
  return parse_off_text(text, path);
}

}  // namespace rad
