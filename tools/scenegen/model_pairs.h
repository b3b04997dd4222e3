// Scenes written two ways that must solve alike (docs/models.md, "The same scene written two
// ways"): a checker-textured floor and the floor cut into coloured squares, a
// cut-out leaf and the leaf cut as polygons, a two-sided screen and two one-sided screens back
// to back, a model as a description and as an OBJ whose every triangle has its own vertices.
// The tests prove each pair agrees; bench/model_pairs_bench.cpp times both sides.
#pragma once

#include <memory>
#include <string>

#include "hierarchy/hierarchy.h"
#include "scene/description.h"

namespace rad {

/// Appends a Pure named `name` made of the quad a b c d (triangles a b c and a c d; front by the
/// right-hand rule), cut into k x k quads.
void add_quad(SceneDescription& s, const std::string& name, Vec3 a, Vec3 b, Vec3 c, Vec3 d,
              Vec3 reflectance, Vec3 emission, int k = 1);

/// The 1 x 1 x 1 room of the pairs below (x, y, z in [0, 1], y up) without its floor: walls
/// x0, x1, z0, z1 and ceiling grey 0.6, and "lamp", a 0.2 x 0.2 panel of emission 20 facing
/// down just under the ceiling's middle.
SceneDescription room_without_floor();

/// The checker of the checker rooms: kCheckerSquares x kCheckerSquares squares of kCheckerTexels
/// / kCheckerSquares texels, light (230, 60, 40) where the square's i + j is even, dark
/// (40, 160, 200) elsewhere (sRGB).
inline constexpr int kCheckerSquares = 4, kCheckerTexels = 64;
std::shared_ptr<TextureImage> checker_texture();

/// A 1 x 1 x 1 room (x, y, z in [0, 1], y up) lit by a 0.2 x 0.2 ceiling panel; its floor the
/// Pure "floor" textured by `checker` (u = x, v = z; factor 1 times the texture's mean; NEAREST
/// magnification, clamped to its edges), or,
/// when not `textured`, cut into Pures "floor i j" of each square's colour as decoded (square
/// (i, j) spans x in [i, i + 1] / kCheckerSquares, z likewise by j).
SceneDescription checker_room(const std::shared_ptr<TextureImage>& checker, bool textured);

/// The checker room lit by its floor alone: the textured floor emits the texture (an emissive
/// texture) or each square emits its colour; nothing reflects there and the panel is dark.
SceneDescription checker_lit_room(const std::shared_ptr<TextureImage>& checker, bool textured);

/// The room of checker_room (floor grey 0.6) with a leaf half-way up (y = 0.5) facing the lamp:
/// the square x, z in [0.2, 0.8] cut out by a mask opaque where x < 0.5, or, when not `cut`, the
/// half x < 0.5 as polygons.
SceneDescription cutout_room(bool cut);

/// The description text of a 2 x 1 x 1 room whose left half has a lamp, with `screen` (objects'
/// text, from screen_object) inside: light reaches the far side of a screen across the middle
/// only over it.
std::string screen_room(const std::string& screen);

/// The text of a Pure screen at x = 1 (z in [0.1, 0.9], up to y = 0.6), reflectance
/// 0.5 <1 0.8 0.6>: facing the lamp (-x), or `turned` over to face away; `flags` as written
/// after Pure (e.g. "TwoSided Yes").
std::string screen_object(const std::string& name, const std::string& flags, bool turned);

/// Writes the Pures of `h` as an OBJ and its MTL beside it (same name, .mtl): every triangle its
/// own three vertices (the unwelded soup many exporters write), one group and material per Pure.
void write_obj_soup(const Hierarchy& h, const std::string& obj_path);

}  // namespace rad
