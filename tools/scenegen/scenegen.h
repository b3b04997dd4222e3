// Deterministic scene generators for tests and benchmarks (scenes built in code, no files).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>

#include "scene/description.h"
#include "scene/description_writer.h"
#include "scene/photometry.h"

namespace rad {

/// The generated scene families.
enum class SceneKind : uint8_t {
  CornellBox,       // "cornell": 5 walls pre-tessellated k × k, a light, two blocks
  Soup,             // "soup": N random triangles in a unit cube, one Pure
  Nested,           // "nested": Assemblies of Assemblies holding Composites of Pures (furniture)
  TeapotInStadium,  // "stadium": a finely tessellated sphere in a large, nearly empty room
  Building,         // "building": N × M rooms with doors, lights and furniture Composites
  FurnishedRoom,    // "room": one room of curved, finely tessellated furniture and a plant
};

const char* to_string(SceneKind kind);

/// How a building's rooms are lit: each by a 1 m² ceiling panel of exitance 8 facing down; by a
/// point light 0.3 m under the ceiling of the panel's on-axis intensity, 8 / pi cd every way
/// (four times the panel's power); or by a downlight where the panel's centre is, whose IES
/// distribution (downlight_ies) is the panel's far field, (8 / pi) cos(gamma) cd downward and
/// none upward: the panel's power, as a light.
struct RoomLighting {
  enum class Kind : uint8_t { Panel, Point, Downlight } kind = Kind::Panel;
  std::shared_ptr<const Photometry> downlight;  // Downlight: parse_ies(downlight_ies(), path)
};

/// The LM-63-2002 text of RoomLighting's downlight: type C, rotationally symmetric, absolute
/// photometry, candela (8 / pi) cos(gamma) at every degree from 0 to 90.
std::string downlight_ies();
/// "cornell" | "soup" | "nested" | "stadium" | "building" | "room"; throws rad::Error otherwise.
SceneKind parse_scene_kind(std::string_view name);

/// A scene of the given family with about `triangles` triangles (within a factor ~1.5; at least
/// a few dozen), the same for the same (kind, triangles, seed) on every platform. A building's
/// rooms get Lights lists (design §8) naming the rooms within `lights_reach` rooms (Chebyshev
/// distance) when it is 0 or more.
/// `lighting` says how a building's rooms are lit; with `light_groups` > 0 they are dealt round
/// that many light groups.
SceneDescription generate_scene(SceneKind kind, uint64_t triangles, uint64_t seed,
                                int lights_reach = -1, const RoomLighting& lighting = {},
                                int light_groups = 0);

/// Cornell box in [0, 1]³ (y up, open front at z = 1): floor, ceiling, back, red left and green
/// right walls each cut into k × k quads (2k² triangles), a light quad under the ceiling and two
/// blocks tessellated about k/4 per face edge. About 11.5 k² triangles.
SceneDescription make_cornell_box(int k);

/// n random triangles with centres uniform in [0, 1]³ and edges about 2/∛n long.
SceneDescription make_triangle_soup(uint64_t n, uint64_t seed);

/// A ground Pure and `blocks` Assemblies of two nested levels, each holding `per_block` furniture
/// Composites (tables and chairs made of box Pures, each face tess × tess quads).
SceneDescription make_nested_scene(int blocks, int per_block, int tess, uint64_t seed);

/// A 100 × 30 × 100 room (inward walls, 8 × 8 quads each), a ceiling light, and a sphere of
/// radius 0.5 with `stacks` × 2·stacks quads at its centre.
SceneDescription make_teapot_in_stadium(int stacks);

/// nx × nz rooms of 5 × 3 × 5 m in one Assembly per row, each room an Assembly of a shell Pure
/// (floor, ceiling, walls with door openings to the neighbours, cut into wall_tess × wall_tess
/// quads per piece), a light, and furniture Composites (a table, chairs, a cabinet) made of boxes
/// with furniture_tess² quads per face. About 1600 triangles per room with the defaults (wall_tess
/// 4, furniture_tess 2). With lights_reach >= 0 each room lights only itself and the rooms
/// within that many rooms along each axis (a Lights list). `lighting` says what lights each room
/// (RoomLighting). With `light_groups` > 0 the rooms are dealt round that many light groups, g0,
/// g1, ... (room i of the building in g(i mod n)).
SceneDescription make_building(int nx, int nz, int wall_tess, int furniture_tess, uint64_t seed,
                               int lights_reach = -1, const RoomLighting& lighting = {},
                               int light_groups = 0);

/// A 5 × 2.8 × 4 m room furnished as real models are made (design §10's curved meshes): a sofa
/// and an armchair of rounded boxes, a coffee table on cylinder legs with a torus, spheres and a
/// vase on it, a bookshelf of boxes, a plant of thin two-sided leaves, a floor lamp whose globe
/// emits (a curved emitter) and a ceiling light panel. Every curved part's tessellation grows
/// with q: about 4,500 q^2 triangles (7,000 at q = 1, 78,000 at q = 4).
SceneDescription make_furnished_room(int q, uint64_t seed);

/// Every triangle cut into k × k congruent triangles of a barycentric grid, same orientation: the
/// surface is exactly the same, only its tessellation changes. Grid points shared by neighbouring
/// triangles are computed by the same expression, so they are equal to the last bit.
std::vector<std::array<Vec3, 3>> tessellate_triangles(const std::vector<std::array<Vec3, 3>>& in,
                                                      int k);

}  // namespace rad
