// Recursive-descent parser for the description grammar of design §2, one function per rule.
#include "scene/parser.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>

#include "scene/ies_reader.h"
#include "scene/model.h"
#include "scene/model_scene.h"
#include "scene/off_reader.h"
#include "scene/text_file.h"
#include "scene/tokenizer.h"

namespace rad {

namespace {

constexpr std::array<std::string_view, 33> kKeywords = {
    "Object",      "Assembly", "Composite", "Pure",      "Reflectivity", "Color",
    "Emission",    "File",     "Data",      "Copy",      "CastsShadows", "ReceivesShadows",
    "TwoSided",    "Lights",   "Yes",       "No",        "Translate",    "Rotate",
    "Scale",       "Model",    "Light",     "Type",      "Point",        "Spot",
    "Directional", "Position", "Direction", "Intensity", "Cone",         "AngularDiameter",
    "Ies",         "IesC0",    "Group"};
constexpr float kDegree = std::numbers::pi_v<float> / 180.0f;
constexpr std::array<const char*, 3> kChannels = {"red", "green", "blue"};

bool is_keyword(std::string_view word) {
  return std::find(kKeywords.begin(), kKeywords.end(), word) != kKeywords.end();
}

// The keyword `word` would be if keywords were not case-sensitive, or "".
std::string_view keyword_ignoring_case(std::string_view word) {
  for (std::string_view k : kKeywords) {
    if (k.size() == word.size() && std::equal(k.begin(), k.end(), word.begin(), [](char a, char b) {
          return std::tolower(static_cast<unsigned char>(a)) ==
                 std::tolower(static_cast<unsigned char>(b));
        })) {
      return k;
    }
  }
  return {};
}

bool is_symbol(const Token& t, char c) {
  return t.kind == TokenKind::Symbol && t.text.size() == 1 && t.text[0] == c;
}

bool is_word(const Token& t, std::string_view word) {
  return t.kind == TokenKind::Word && t.text == word;
}

std::string fmt_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

class Parser {
 public:
  Parser(std::string_view text, const std::string& path) : tokens_(text, path) {
    scene_.path = path;
  }

  // Scene ::= String Composition
  SceneDescription parse_scene() {
    scene_.name = expect_string("the scene's name (a quoted string)");
    // Composition ::= Complex Composition | Complex, up to the end of the file.
    while (true) {
      const Token& t = tokens_.peek();
      if (t.kind == TokenKind::End && !scene_.roots.empty()) break;
      scene_.roots.push_back(parse_object(
          /*in_composite=*/false, scene_.roots.empty() ? "'Object'" : "'Object' or end of file"));
    }
    return std::move(scene_);
  }

 private:
  [[noreturn]] void fail_expected(const Token& found, const std::string& expected,
                                  bool keyword_expected, const std::string& prefix = "") {
    if (found.kind == TokenKind::End) {
      throw Error(found.loc, prefix + "unexpected end of file: expected " + expected);
    }
    if (keyword_expected && found.kind == TokenKind::Word && !is_keyword(found.text) &&
        parse_number(found.text).status == NumberParse::NotANumber) {
      std::string message = prefix + "unknown keyword '" + found.text + "': expected " + expected;
      std::string_view hint = keyword_ignoring_case(found.text);
      if (!hint.empty()) {
        message += " (keywords are case-sensitive: '" + std::string(hint) + "')";
      }
      throw Error(found.loc, message);
    }
    throw Error(found.loc, prefix + "expected " + expected + " but found " + describe(found));
  }

  Token expect_keyword(std::string_view keyword) {
    Token t = tokens_.next();
    if (!is_word(t, keyword)) fail_expected(t, "'" + std::string(keyword) + "'", true);
    return t;
  }

  Token expect_symbol(char c, const std::string& context = "") {
    Token t = tokens_.next();
    if (!is_symbol(t, c)) fail_expected(t, std::string("'") + c + "'" + context, false);
    return t;
  }

  std::string expect_string(const std::string& what) {
    Token t = tokens_.next();
    if (t.kind != TokenKind::String) fail_expected(t, what, false);
    return t.text;
  }

  // Real, finite. `where` receives the token (for later validation messages).
  double expect_number(const std::string& what, Token& where) {
    where = tokens_.next();
    if (where.kind != TokenKind::Word) fail_expected(where, what, false);
    NumberParse n = parse_number(where.text);
    if (n.status == NumberParse::NonFinite) {
      throw Error(where.loc, "non-finite number '" + where.text + "': expected " + what);
    }
    if (n.status == NumberParse::NotANumber) fail_expected(where, what, false);
    return n.value;
  }

  // Vector ::= "<" Real Real Real ">"
  DVec3 expect_vector(const std::string& what, std::array<Token, 3>& where) {
    Token open = tokens_.next();
    if (!is_symbol(open, '<')) fail_expected(open, "'<' starting " + what, false);
    DVec3 v;
    for (int k = 0; k < 3; ++k) v[k] = expect_number("a number", where[k]);
    expect_symbol('>', " closing " + what);
    return v;
  }

  // Complex ::= "Object" String (Assembly | Composite | Pure); Simple when in a Composite.
  int32_t parse_object(bool in_composite, const std::string& expected) {
    Token object = tokens_.next();
    if (!is_word(object, "Object")) fail_expected(object, expected, true);
    // The parser and every walk of the hierarchy recurse: bound the depth, not the stack.
    if (depth_ >= kMaxNesting) {
      throw Error(object.loc, fmt::format("objects nested more than {} deep", kMaxNesting));
    }
    struct Depth {
      int& d;
      explicit Depth(int& x) : d(++x) {}
      ~Depth() { --d; }
    } nested(depth_);
    std::string name = expect_string("the object's name (a quoted string)");
    Token kind = tokens_.next();
    ObjectKind k;
    int32_t copy_of = -1;
    bool light = false;
    Token model_file;
    if (is_word(kind, "Copy")) {
      // Copy "name": the latest complete object of that name (so never one that is open).
      const Token original = tokens_.next();
      if (original.kind != TokenKind::String) {
        fail_expected(original, "the name of the object to copy (a quoted string)", false);
      }
      for (size_t i = scene_.objects.size(); i-- > 0;) {
        if (complete_[i] && scene_.objects[i].name == original.text) {
          copy_of = int32_t(i);
          break;
        }
      }
      if (copy_of < 0) {
        throw Error(original.loc,
                    "no object \"" + original.text + "\" is defined before this copy");
      }
      k = scene_.objects[size_t(copy_of)].kind;
      for (int32_t o = copy_of; o >= 0; o = scene_.objects[size_t(o)].copy_of)
        light |= scene_.objects[size_t(o)].light.has_value();
    } else if (is_word(kind, "Model")) {
      // Model "file": the whole model, its groups and materials, as an Assembly (design §8).
      model_file = tokens_.next();
      if ((model_file.kind != TokenKind::Word && model_file.kind != TokenKind::String) ||
          model_file.text.empty()) {
        fail_expected(model_file, "a model file's name", false);
      }
      k = ObjectKind::Assembly;
    } else if (is_word(kind, "Assembly")) {
      k = ObjectKind::Assembly;
    } else if (is_word(kind, "Composite")) {
      k = ObjectKind::Composite;
    } else if (is_word(kind, "Pure")) {
      k = ObjectKind::Pure;
    } else if (is_word(kind, "Light")) {
      k = ObjectKind::Pure;  // a leaf, as ObjectDescription::light says
      light = true;
    } else {
      fail_expected(kind,
                    in_composite ? "'Pure', 'Light' or 'Copy'"
                                 : "'Assembly', 'Composite', 'Pure', 'Light', 'Copy' or 'Model'",
                    true);
    }
    if (in_composite && k != ObjectKind::Pure) {
      throw Error(kind.loc, "a Composite holds only Pures, but \"" + name + "\" is " +
                                (k == ObjectKind::Assembly ? "an Assembly" : "a Composite"));
    }
    auto id = static_cast<int32_t>(scene_.objects.size());
    ObjectDescription d;
    d.name = name;
    d.kind = k;
    d.loc = object.loc;
    d.copy_of = copy_of;
    const bool model = !model_file.text.empty();
    d.flags = parse_flags(d.transforms, /*body=*/copy_of < 0 && !model);
    if (light && d.flags.group) {
      throw Error(kind.loc,
                  "a Light's group goes inside its braces: Light { Type ... Group \"name\" }");
    }
    if (light && (d.flags.casts_shadows || d.flags.receives_shadows || d.flags.two_sided ||
                  d.flags.has_lights)) {
      throw Error(kind.loc,
                  "a Light takes Translate, Rotate and Scale, not CastsShadows, "
                  "ReceivesShadows, TwoSided or Lights (it is not a surface)");
    }
    scene_.objects.push_back(std::move(d));
    complete_.push_back(0);
    if (model) graft_model(id, model_file);
    if (copy_of >= 0 || model) {
      complete_[size_t(id)] = 1;
      return id;
    }
    if (light) {
      parse_light(id);
      complete_[size_t(id)] = 1;
      return id;
    }
    switch (k) {
      case ObjectKind::Assembly:
        parse_group(id, /*pures_only=*/false);
        break;
      case ObjectKind::Composite:
        parse_group(id, /*pures_only=*/true);
        break;
      case ObjectKind::Pure:
        parse_pure(id);
        break;
    }
    complete_[size_t(id)] = 1;
    return id;
  }

  // The model's scene (model_scene.h) below object `id`: its groups become Composites, its
  // (group, material) pairs Pures with the model's own materials.
  void graft_model(int32_t id, const Token& file) {
    namespace fs = std::filesystem;
    const fs::path full = (fs::path(scene_.path).parent_path() / file.text).lexically_normal();
    if (!is_model_file(full.string())) {
      throw Error(file.loc, "'" + file.text + "' is not a model (.obj, .ply, .gltf or .glb)");
    }
    // The model's Composites and Pures nest two deeper than the Model object (model_scene.h).
    if (depth_ + 2 > kMaxNesting) {
      throw Error(file.loc, fmt::format("objects nested more than {} deep (with the model's "
                                        "groups and Pures)",
                                        kMaxNesting));
    }
    ModelOptions o;
    o.require_emission = false;  // the description's other objects may hold the lights
    const SceneDescription m = model_to_scene(read_model_file(full.string(), file.loc), o);
    const int32_t base = int32_t(scene_.objects.size()) - 1;  // the model's root is `id`
    for (size_t i = 1; i < m.objects.size(); ++i) {
      ObjectDescription c = m.objects[i];
      for (int32_t& child : c.children) child += base;
      scene_.objects.push_back(std::move(c));
      complete_.push_back(0);  // the model's own pieces: a Copy names the Model object, not them
    }
    for (int32_t child : m.objects[0].children)
      scene_.objects[size_t(id)].children.push_back(child + base);
    if (scene_.objects[size_t(id)].children.empty()) {
      throw Error(file.loc, "the model '" + file.text + "' has no triangles");
    }
  }

  // Flags ::= Flag Flags | (nothing)
  // Flag  ::= "CastsShadows" YesNo | "ReceivesShadows" YesNo | "TwoSided" YesNo
  //         | "Lights" "{" Strings "}" | "Group" String
  //         | "Translate" Vector | "Rotate" Vector Real | "Scale" (Real | Vector)
  // Transforms are kept in the order written. With `body`, a '{' must follow.
  ObjectFlags parse_flags(std::vector<Transform>& transforms, bool body) {
    ObjectFlags f;
    for (;;) {
      const Token& t = tokens_.peek();
      if (is_word(t, "Translate") || is_word(t, "Rotate") || is_word(t, "Scale")) {
        transforms.push_back(parse_transform());
        continue;
      }
      if (is_word(t, "CastsShadows") || is_word(t, "ReceivesShadows") || is_word(t, "TwoSided")) {
        const Token flag = tokens_.next();
        std::optional<bool>& slot = flag.text == "CastsShadows"      ? f.casts_shadows
                                    : flag.text == "ReceivesShadows" ? f.receives_shadows
                                                                     : f.two_sided;
        if (slot) throw Error(flag.loc, "'" + flag.text + "' given twice for one object");
        const Token value = tokens_.next();
        if (!is_word(value, "Yes") && !is_word(value, "No")) {
          fail_expected(value, "'Yes' or 'No' after '" + flag.text + "'", true);
        }
        slot = value.text == "Yes";
      } else if (is_word(t, "Group")) {
        const Token flag = tokens_.next();
        if (f.group) throw Error(flag.loc, "'Group' given twice for one object");
        f.group = expect_string("the light group's name (a quoted string)");
      } else if (is_word(t, "Lights")) {
        const Token flag = tokens_.next();
        if (f.has_lights) throw Error(flag.loc, "'Lights' given twice for one object");
        f.has_lights = true;
        expect_symbol('{', " after 'Lights'");
        while (!is_symbol(tokens_.peek(), '}')) {
          const Token name = tokens_.next();
          if (name.kind != TokenKind::String) {
            fail_expected(name, "an object's name (a quoted string) or '}'", false);
          }
          f.lights.push_back({name.text, name.loc});
        }
        tokens_.next();
      } else {
        if (body && !is_symbol(t, '{')) {
          fail_expected(
              t,
              "a transform, 'CastsShadows', 'ReceivesShadows', 'TwoSided', 'Lights', 'Group' "
              "or '{'",
              true);
        }
        return f;
      }
    }
  }

  // One transform, checked.
  Transform parse_transform() {
    const Token op = tokens_.next();
    std::array<Token, 3> where;
    Transform t;
    if (op.text == "Translate") {
      t.v = expect_vector("the translation", where);
      return t;
    }
    if (op.text == "Rotate") {
      t.kind = Transform::Kind::Rotate;
      t.v = expect_vector("the rotation's axis", where);
      if (!(glm::length(t.v) > 0.0)) throw Error(where[0].loc, "the rotation's axis is zero");
      Token angle;
      t.degrees = expect_number("the rotation's angle in degrees", angle);
      return t;
    }
    t.kind = Transform::Kind::Scale;
    if (is_symbol(tokens_.peek(), '<')) {
      t.v = expect_vector("the scale factors", where);
    } else {
      t.v = DVec3(expect_number("the scale factor (a number or a vector)", where[0]));
      where[1] = where[2] = where[0];
    }
    for (int k = 0; k < 3; ++k) {
      if (!(t.v[k] != 0.0))
        throw Error(where[size_t(k)].loc, "a scale factor of 0 flattens the object");
    }
    return t;
  }

  // Light ::= "Light" Flags "{" "Type" LightType LightProperties "}"
  // LightType ::= "Point" | "Spot" | "Directional"
  // LightProperty ::= "Position" Vector | "Direction" Vector | "Color" Vector | "Intensity" Real
  //                 | "Cone" Real Real | "AngularDiameter" Real | "Ies" FileName
  //                 | "IesC0" Vector | "Group" String        (any order, each at most once)
  void parse_light(int32_t id) {
    expect_symbol('{');
    expect_keyword("Type");
    const Token type = tokens_.next();
    Light l;
    l.name = scene_.objects[size_t(id)].name;
    l.loc = scene_.objects[size_t(id)].loc;
    if (is_word(type, "Point")) {
      l.kind = LightKind::Point;
    } else if (is_word(type, "Spot")) {
      l.kind = LightKind::Spot;
    } else if (is_word(type, "Directional")) {
      l.kind = LightKind::Directional;
    } else {
      fail_expected(type, "'Point', 'Spot' or 'Directional' after 'Type'", true);
    }
    const char* kind = to_string(l.kind);
    const bool directional = l.kind == LightKind::Directional;
    std::vector<std::string> seen;
    std::optional<Token> position, direction, intensity, ies, c0;
    Vec3 up(0.0f);
    for (;;) {
      const Token t = tokens_.next();
      if (is_symbol(t, '}')) {
        // What the light needs, said at its end.
        auto need = [&](bool missing, const std::string& what) {
          if (missing)
            throw Error(t.loc, fmt::format("{} light \"{}\" has no {}", kind, l.name, what));
        };
        need(!directional && !position, "Position (where it is: Position <x y z>)");
        need(l.kind != LightKind::Point && !direction,
             "Direction (where it shines: Direction <x y z>, e.g. <0 -1 0>)");
        need(!intensity && !ies,
             directional ? "Intensity (its illuminance in lux: Intensity 100000 for full sun)"
                         : "Intensity (candela: Intensity 100), nor an Ies file");
        break;
      }
      const bool property =
          t.kind == TokenKind::Word &&
          (t.text == "Position" || t.text == "Direction" || t.text == "Color" ||
           t.text == "Intensity" || t.text == "Cone" || t.text == "AngularDiameter" ||
           t.text == "Ies" || t.text == "IesC0" || t.text == "Group");
      if (!property) {
        fail_expected(t,
                      directional ? "'Direction', 'Color', 'Intensity', 'AngularDiameter', "
                                    "'Group' or '}'"
                      : l.kind == LightKind::Spot
                          ? "'Position', 'Direction', 'Color', 'Intensity', 'Cone', 'Ies', "
                            "'IesC0', 'Group' or '}'"
                          : "'Position', 'Color', 'Intensity', 'Ies', 'Direction', 'IesC0', "
                            "'Group' or '}'",
                      true);
      }
      if (std::find(seen.begin(), seen.end(), t.text) != seen.end()) {
        throw Error(t.loc, "'" + t.text + "' given twice for one light");
      }
      seen.push_back(t.text);
      auto only = [&](bool allowed, const std::string& why) {
        if (!allowed) throw Error(t.loc, fmt::format("a {} light has no {}", kind, why));
      };
      std::array<Token, 3> w;
      if (t.text == "Position") {
        only(!directional, "Position: the sun shines from far away along its Direction");
        position = t;
        l.position = Vec3(expect_vector("the light's position", w));
      } else if (t.text == "Direction") {
        direction = t;
        const DVec3 d = expect_vector("the light's direction", w);
        if (!(glm::length(d) > 0.0) || !std::isfinite(glm::length(d))) {
          throw Error(w[0].loc,
                      "the light's direction is zero: give where it shines, e.g. "
                      "<0 -1 0> (straight down when y is up)");
        }
        l.direction = Vec3(glm::normalize(d));
      } else if (t.text == "Color") {
        const DVec3 c = expect_vector("the light's colour", w);
        for (int k = 0; k < 3; ++k) {
          if (c[k] < 0.0) {
            throw Error(w[size_t(k)].loc, std::string("negative ") + kChannels[size_t(k)] +
                                              " colour component " + w[size_t(k)].text);
          }
        }
        l.colour = Vec3(c);
      } else if (t.text == "Intensity") {
        Token v;
        intensity = t;
        const double i = expect_number(
            directional ? "the intensity in lux (a number)" : "the intensity in candela (a number)",
            v);
        if (i < 0.0) throw Error(v.loc, "negative intensity " + v.text);
        l.intensity = float(i);
        if (!std::isfinite(l.intensity))
          throw Error(v.loc, "intensity " + v.text + " is too large");
      } else if (t.text == "Cone") {
        only(l.kind == LightKind::Spot, "Cone: only a spot light has one");
        Token a, b;
        const double inner = expect_number("the inner cone's half-angle in degrees", a);
        const double outer = expect_number("the outer cone's half-angle in degrees", b);
        if (inner < 0.0) throw Error(a.loc, "negative inner cone angle " + a.text);
        if (!(outer > 0.0) || outer > 90.0) {
          throw Error(b.loc, "outer cone angle " + b.text +
                                 " is not above 0 and at most 90 degrees (a half-angle from the "
                                 "axis; for light every way use a point light)");
        }
        if (inner > outer) {
          throw Error(a.loc, "the inner cone (" + a.text + " degrees) is wider than the outer (" +
                                 b.text +
                                 "): Cone INNER OUTER, full intensity within the inner, "
                                 "none beyond the outer");
        }
        l.inner_cone = float(inner) * kDegree;
        l.outer_cone = float(outer) * kDegree;
      } else if (t.text == "AngularDiameter") {
        only(directional, "AngularDiameter: only a directional light (the sun) has one");
        Token v;
        const double a = expect_number("the angular diameter in degrees", v);
        if (!(a >= 0.0 && a < 90.0)) {
          throw Error(v.loc, "angular diameter " + v.text +
                                 " is outside 0 (sharp shadows) to under 90 degrees (the sun's "
                                 "is 0.53)");
        }
        l.angular_diameter = float(a) * kDegree;
      } else if (t.text == "Ies") {
        only(!directional, "Ies file: give a point or spot light the luminaire's file");
        const Token file = tokens_.next();
        if ((file.kind != TokenKind::Word && file.kind != TokenKind::String) || file.text.empty()) {
          fail_expected(file, "an IES file's name", false);
        }
        ies = file;
        namespace fs = std::filesystem;
        const std::string full =
            (fs::path(scene_.path).parent_path() / file.text).lexically_normal().string();
        auto it = photometry_.find(full);
        if (it == photometry_.end())
          it = photometry_.emplace(full, read_ies_file(full, file.loc)).first;
        l.photometry = it->second;
      } else if (t.text == "IesC0") {
        c0 = t;
        up = Vec3(expect_vector("the direction of the IES file's C0 plane", w));
        if (!(glm::length(up) > 0.0f)) throw Error(w[0].loc, "the IesC0 direction is zero");
      } else {  // Group
        l.group = expect_string("the light group's name (a quoted string)");
      }
    }
    if (c0 && !ies) throw Error(c0->loc, "'IesC0' orients an IES file: give the light an 'Ies'");
    if (l.kind == LightKind::Point && direction && !ies) {
      throw Error(direction->loc,
                  "a point light shines every way: its 'Direction' only aims an "
                  "'Ies' file's nadir; remove it or use a Spot");
    }
    if (!intensity) l.intensity = 1.0f;  // with an IES file: its candela as they are
    if (l.kind == LightKind::Point && !direction) l.direction = Vec3(0.0f, -1.0f, 0.0f);
    if (c0) {
      const Vec3 p = up - l.direction * glm::dot(up, l.direction);
      if (!(glm::length(p) > 1e-3f * glm::length(up))) {
        throw Error(c0->loc,
                    "the IesC0 direction lies along the light's direction: give one "
                    "across it (the luminaire's C0 reference direction)");
      }
      l.photometric_up = glm::normalize(p);
    } else {
      l.photometric_up = default_photometric_up(l.direction);
    }
    check_light(l);
    scene_.objects[size_t(id)].light = std::move(l);
  }

  // Assembly ::= "Assembly" "{" Composition "}";  Composite ::= "Composite" "{" Objects "}"
  void parse_group(int32_t id, bool pures_only) {
    expect_symbol('{');
    std::vector<int32_t> children;
    while (true) {
      const Token& t = tokens_.peek();
      if (is_symbol(t, '}')) {
        if (children.empty()) {
          const ObjectDescription& d = scene_.objects[id];
          fail_expected(t, "'Object'", false,
                        "empty " + std::string(to_string(d.kind)) + " \"" + d.name + "\": ");
        }
        tokens_.next();
        break;
      }
      children.push_back(
          parse_object(pures_only, children.empty() ? "'Object'" : "'Object' or '}'"));
    }
    scene_.objects[id].children = std::move(children);
  }

  // Pure ::= "Pure" "{" Characteristics Geometry "}"
  // Characteristics ::= "Reflectivity" Real "Color" Vector "Emission" Real
  void parse_pure(int32_t id) {
    expect_symbol('{');
    expect_keyword("Reflectivity");
    Token r_token;
    double reflectivity = expect_number("the reflectivity (a number)", r_token);
    if (reflectivity < 0.0) {
      throw Error(r_token.loc, "negative reflectivity " + r_token.text);
    }
    expect_keyword("Color");
    std::array<Token, 3> c_tokens;
    DVec3 color = expect_vector("the colour", c_tokens);
    for (int k = 0; k < 3; ++k) {
      if (color[k] < 0.0) {
        throw Error(c_tokens[k].loc, std::string("negative ") + kChannels[k] +
                                         " colour component " + c_tokens[k].text);
      }
      double rho = reflectivity * color[k];
      if (rho > 1.0) {
        throw Error(c_tokens[k].loc, std::string("reflectance ") + fmt_number(rho) +
                                         " (Reflectivity " + r_token.text + " x Color " +
                                         c_tokens[k].text + ") of the " + kChannels[k] +
                                         " channel is outside [0, 1]");
      }
    }
    expect_keyword("Emission");
    Token e_token;
    double emission = expect_number("the emission (a number)", e_token);
    if (emission < 0.0) throw Error(e_token.loc, "negative emission " + e_token.text);

    Material& m = scene_.objects[id].material;
    m.reflectance = Vec3(reflectivity * color);
    m.emission = Vec3(emission * color);
    parse_geometry(scene_.objects[id]);
    expect_symbol('}', " closing the Pure");
  }

  // Geometry ::= "File" FileName | "Data" "{" Polys "}"
  void parse_geometry(ObjectDescription& pure) {
    Token g = tokens_.next();
    if (is_word(g, "File")) {
      Token file = tokens_.next();
      if ((file.kind != TokenKind::Word && file.kind != TokenKind::String) || file.text.empty()) {
        fail_expected(file, "a file name", false);
      }
      namespace fs = std::filesystem;
      fs::path full = (fs::path(scene_.path).parent_path() / file.text).lexically_normal();
      if (is_model_file(full.string())) {
        // A model's triangles, all of them, with this Pure's material (its own are ignored).
        Model model = read_model_file(full.string(), file.loc);
        for (ModelGroup& group : model.groups) {
          pure.triangles.insert(pure.triangles.end(), group.triangles.begin(),
                                group.triangles.end());
          pure.triangle_locs.insert(pure.triangle_locs.end(), group.triangle_locs.begin(),
                                    group.triangle_locs.end());
        }
        return;
      }
      OffTriangles off = read_off_file(full.string(), file.loc);
      pure.triangles = std::move(off.triangles);
      pure.triangle_locs = std::move(off.triangle_locs);
    } else if (is_word(g, "Data")) {
      parse_data(pure);
    } else {
      fail_expected(g, "'File' or 'Data'", true);
    }
  }

  // Polys ::= Poly Polys | Poly;  Poly ::= Vector Vector Vector
  void parse_data(ObjectDescription& pure) {
    expect_symbol('{');
    while (true) {
      const Token& t = tokens_.peek();
      if (is_symbol(t, '}')) {
        if (pure.triangles.empty()) {
          fail_expected(t, "'<'", false, "empty Data in \"" + pure.name + "\": ");
        }
        tokens_.next();
        return;
      }
      SourceLoc loc = t.loc;
      std::array<Vec3, 3> triangle;
      std::array<Token, 3> ignored;
      for (int corner = 0; corner < 3; ++corner) {
        const Token& p = tokens_.peek();
        if (corner > 0 && is_symbol(p, '}')) {
          throw Error(p.loc,
                      "expected '<' but found '}': a triangle needs 3 corners, this one has " +
                          std::to_string(corner));
        }
        triangle[corner] = Vec3(expect_vector(corner == 0 ? "a triangle" : "a corner", ignored));
      }
      pure.triangles.push_back(triangle);
      pure.triangle_locs.push_back(std::move(loc));
    }
  }

  Tokenizer tokens_;
  std::map<std::string, std::shared_ptr<const Photometry>> photometry_;  // IES files read, by path
  std::vector<char> complete_;             // per object: parsed to its end (a copy may name it)
  int depth_ = 0;                          // objects open around the one being parsed
  static constexpr int kMaxNesting = 256;  // real scenes nest a few deep; ASan frames are large
  SceneDescription scene_;
};

}  // namespace

SceneDescription parse_scene_text(std::string_view text, const std::string& path) {
  return Parser(text, path).parse_scene();
}

SceneDescription parse_scene_file(const std::string& path) {
  std::string text = read_text_file(path, SourceLoc{path});
  return parse_scene_text(text, path);
}

}  // namespace rad
