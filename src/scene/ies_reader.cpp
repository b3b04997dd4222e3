#include "scene/ies_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "scene/text_file.h"
#include "scene/tokenizer.h"

namespace rad {

namespace {

// Large enough for any real luminaire (the finest files measure every 0.5 degrees: 361 x 721),
// small enough that a hostile count never becomes a huge table.
constexpr long long kMaxAngles = 10'000;
constexpr size_t kMaxValues = 4'000'000;

struct Word {
  std::string_view text;
  SourceLoc loc;
};

// The numbers after the TILT line: words separated by blanks or commas, with their places.
class Numbers {
 public:
  Numbers(std::string_view text, size_t pos, int line, size_t line_start, std::string path)
      : text_(text), pos_(pos), line_(line), line_start_(line_start), path_(std::move(path)) {}

  // The next word, or one with empty text at the end of the file.
  Word next() {
    while (pos_ < text_.size() && separates(text_[pos_])) {
      if (text_[pos_] == '\n' || (text_[pos_] == '\r' && next_is_not('\n'))) {
        ++line_;
        line_start_ = pos_ + 1;
      }
      ++pos_;
    }
    Word w;
    w.loc = SourceLoc{path_, line_, int(pos_ - line_start_) + 1};
    const size_t start = pos_;
    while (pos_ < text_.size() && !separates(text_[pos_])) ++pos_;
    w.text = text_.substr(start, pos_ - start);
    if (w.text.empty()) {
      if (last_end_.line > 0) w.loc = last_end_;  // the end: just after the last value
    } else {
      last_end_ = SourceLoc{path_, line_, int(pos_ - line_start_) + 1};
    }
    return w;
  }

  // Where the next word starts (or the text ends), without taking it.
  SourceLoc peek_loc() {
    const size_t save = pos_;
    const int line = line_;
    const size_t start = line_start_;
    const SourceLoc last = last_end_;
    SourceLoc l = next().loc;
    pos_ = save, line_ = line, line_start_ = start, last_end_ = last;
    return l;
  }

  const std::string& path() const { return path_; }

 private:
  static bool separates(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == ',' || c == '\f' || c == '\v';
  }
  bool next_is_not(char c) const { return pos_ + 1 >= text_.size() || text_[pos_ + 1] != c; }

  std::string_view text_;
  size_t pos_;
  int line_;
  size_t line_start_;
  std::string path_;
  SourceLoc last_end_;  // just after the last word read
};

std::string shown(std::string_view w) {
  std::string s(w.substr(0, 40));
  for (char& c : s) {
    if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
  }
  return w.size() > 40 ? s + "..." : s;
}

class Reader {
 public:
  explicit Reader(Numbers n) : n_(std::move(n)) {}

  // A finite number, `what` naming it in the error.
  double number(const std::string& what, SourceLoc* where = nullptr) {
    const Word w = n_.next();
    if (w.text.empty()) {
      throw Error(w.loc, "unexpected end of file: expected " + what +
                             " (the file is truncated, or a count above promises more values "
                             "than it holds)");
    }
    const NumberParse p = parse_number(w.text);
    if (p.status != NumberParse::Ok) {
      throw Error(w.loc, "'" + shown(w.text) + "' is not " +
                             (p.status == NumberParse::NonFinite ? "a finite number" : "a number") +
                             ": expected " + what);
    }
    if (where) *where = w.loc;
    return p.value;
  }

  // A whole number within [lo, hi].
  long long integer(const std::string& what, long long lo, long long hi) {
    SourceLoc at;
    const double v = number(what, &at);
    if (v != std::floor(v) || v < double(lo) || v > double(hi)) {
      throw Error(
          at, fmt::format("{} is {:g}, but must be a whole number from {} to {}", what, v, lo, hi));
    }
    return (long long)v;
  }

  // A number above 0 (or >= 0 with `zero_ok`).
  double positive(const std::string& what, bool zero_ok = false) {
    SourceLoc at;
    const double v = number(what, &at);
    if (zero_ok ? !(v >= 0.0) : !(v > 0.0)) {
      throw Error(at, fmt::format("{} is {:g}, but must be {}", what, v,
                                  zero_ok ? "0 or more" : "above 0"));
    }
    return v;
  }

  // `count` angles, strictly increasing, within [lo, hi].
  std::vector<float> angles(long long count, const char* kind, double lo, double hi) {
    std::vector<float> a;
    for (long long i = 0; i < count; ++i) {
      SourceLoc at;
      const double v = number(fmt::format("{} angle {} of {}", kind, i + 1, count), &at);
      if (v < lo || v > hi) {
        throw Error(at, fmt::format("{} angle {:g} is outside {:g} to {:g} degrees, the range of "
                                    "type C photometry",
                                    kind, v, lo, hi));
      }
      if (!a.empty() && !(float(v) > a.back())) {
        throw Error(at, fmt::format("{} angle {:g} does not increase from the one before ({:g}): "
                                    "the angles must be listed in increasing order",
                                    kind, v, double(a.back())));
      }
      a.push_back(float(v));
    }
    return a;
  }

  Numbers n_;
};

// The line's text without its end and surrounding blanks.
std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

bool starts_with_tilt(std::string_view line) {
  if (line.size() < 4) return false;
  for (size_t i = 0; i < 4; ++i) {
    if (std::toupper(static_cast<unsigned char>(line[i])) != "TILT"[i]) return false;
  }
  line.remove_prefix(4);
  line = trimmed(line);
  return !line.empty() && line.front() == '=';
}

}  // namespace

Photometry parse_ies(std::string_view text, const std::string& path) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  // The header: any lines (an IESNA:LM-63-... line, [KEYWORD] lines, a 1986 file's free text)
  // up to the TILT= line.
  size_t pos = 0;
  int line = 1;
  std::string_view tilt;
  SourceLoc tilt_loc;
  while (pos < text.size()) {
    size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view l = trimmed(text.substr(pos, end - pos));
    size_t next = end;  // past the line's end: "\r\n", "\n" or "\r"
    if (next < text.size()) next += text.compare(next, 2, "\r\n") == 0 ? 2 : 1;
    if (starts_with_tilt(l)) {
      tilt = trimmed(l.substr(l.find('=') + 1));
      tilt_loc = SourceLoc{path, line, 1};
      pos = next;
      ++line;
      break;
    }
    pos = next;
    ++line;
  }
  if (tilt_loc.line == 0) {
    throw Error(SourceLoc{path, 1, 1},
                "no TILT= line: not an IES LM-63 photometric file (its header ends with a line "
                "TILT=NONE, then the numbers)");
  }
  Reader r(Numbers(text, pos, line, pos, path));
  if (tilt == "INCLUDE" || tilt == "include") {
    // Lamp-to-luminaire geometry, the number of tilt angles, the angles, their factors.
    r.integer("the TILT=INCLUDE lamp-to-luminaire geometry", 1, 3);
    const long long n = r.integer("the number of tilt angles", 0, kMaxAngles);
    for (long long i = 0; i < 2 * n; ++i) {
      r.number(i < n ? "a tilt angle" : "a tilt multiplying factor");
    }
    warn(tilt_loc,
         "TILT=INCLUDE: the lamp's tilt factors are not applied (rad takes the "
         "luminaire as measured)");
  } else if (tilt != "NONE" && tilt != "none") {
    warn(tilt_loc, "TILT=" + shown(tilt) +
                       ": the tilt file is not read and its factors are not applied (rad takes "
                       "the luminaire as measured)");
  }

  Photometry p;
  p.path = path;
  p.lamps = int(r.integer("the number of lamps", 1, 1'000'000));
  {
    SourceLoc at;
    const double lm = r.number("the lumens per lamp (-1 for absolute photometry)", &at);
    if (!(lm > 0.0 || lm == -1.0)) {
      throw Error(at, fmt::format("the lumens per lamp are {:g}, but must be above 0, or -1 for "
                                  "absolute photometry",
                                  lm));
    }
    p.lumens_per_lamp = float(lm);
  }
  p.multiplier = float(r.positive("the candela multiplier"));
  const long long nv = r.integer("the number of vertical angles", 2, kMaxAngles);
  const long long nh = r.integer("the number of horizontal angles", 1, kMaxAngles);
  {
    SourceLoc at;
    const double type = r.number("the photometric type (1 for type C)", &at);
    if (type == 2.0 || type == 3.0) {
      throw Error(
          at, fmt::format("photometric type {} (type {}): rad reads type C photometry (type 1), "
                          "what building luminaires are measured in; ask the "
                          "manufacturer for a type C file",
                          type, type == 2.0 ? "B" : "A"));
    }
    if (type != 1.0) {
      throw Error(at,
                  fmt::format("photometric type {:g}: expected 1 (type C), 2 (B) or 3 (A)", type));
    }
  }
  r.integer("the units type (1 feet, 2 metres)", 1, 2);
  r.number("the luminaire's width");
  r.number("the luminaire's length");
  r.number("the luminaire's height");
  p.ballast_factor = float(r.positive("the ballast factor"));
  p.ballast_lamp_factor = float(r.positive("the ballast-lamp photometric factor (future use)"));
  p.input_watts = float(r.number("the input watts"));
  if (size_t(nv) * size_t(nh) > kMaxValues) {
    throw Error(SourceLoc{path, line, 1},
                fmt::format("{} vertical by {} horizontal angles is more than {} candela values",
                            nv, nh, kMaxValues));
  }
  p.vertical = r.angles(nv, "vertical", 0.0, 180.0);
  SourceLoc first_h = r.n_.peek_loc();
  p.horizontal = r.angles(nh, "horizontal", 0.0, 360.0);
  const float h0 = p.horizontal.front(), h1 = p.horizontal.back();
  auto near = [](float a, float b) { return std::abs(a - b) <= 1e-3f; };
  if (nh == 1) {
    p.symmetry = CSymmetry::Rotational;
  } else if (near(h0, 0.0f) && near(h1, 90.0f)) {
    p.symmetry = CSymmetry::Quadrant;
  } else if (near(h0, 0.0f) && near(h1, 180.0f)) {
    p.symmetry = CSymmetry::Bilateral;
  } else if (near(h0, 90.0f) && near(h1, 270.0f)) {
    p.symmetry = CSymmetry::Bilateral90;
  } else if (near(h0, 0.0f) && near(h1, 360.0f)) {
    p.symmetry = CSymmetry::Full;
  } else {
    throw Error(first_h, fmt::format("horizontal angles from {:g} to {:g} degrees: type C files "
                                     "give one angle (rotationally symmetric), or 0 to 90, 0 to "
                                     "180, 90 to 270 or 0 to 360 degrees",
                                     double(h0), double(h1)));
  }
  const double scale = double(p.multiplier) * p.ballast_factor * p.ballast_lamp_factor;
  // Each value takes two characters at least: a count the text cannot hold reserves no more.
  p.candela.reserve(std::min(size_t(nv * nh), text.size() / 2));
  for (long long h = 0; h < nh; ++h) {
    for (long long v = 0; v < nv; ++v) {
      SourceLoc at;
      const double cd = r.number(
          fmt::format("the candela value at vertical angle {:g} of horizontal angle {:g} ({} "
                      "values: {} vertical by {} horizontal angles)",
                      double(p.vertical[size_t(v)]), double(p.horizontal[size_t(h)]), nv * nh, nv,
                      nh),
          &at);
      if (cd < 0.0) throw Error(at, fmt::format("negative candela value {:g}", cd));
      const float value = float(cd * scale);
      if (!std::isfinite(value)) {
        throw Error(at, fmt::format("candela value {:g} times the multiplier and factors is too "
                                    "large",
                                    cd));
      }
      p.candela.push_back(value);
      p.max_candela = std::max(p.max_candela, value);
    }
  }
  const Word extra = r.n_.next();
  if (!extra.text.empty()) {
    throw Error(extra.loc, fmt::format("'{}' after the candela table: {} vertical by {} horizontal "
                                       "angles make {} values, and the file holds more (check "
                                       "the two counts)",
                                       shown(extra.text), nv, nh, nv * nh));
  }
  return p;
}

std::shared_ptr<const Photometry> read_ies_file(const std::string& path,
                                                const SourceLoc& requested_at) {
  const std::string text = read_text_file(path, requested_at);
  return std::make_shared<const Photometry>(parse_ies(text, path));
}

}  // namespace rad
