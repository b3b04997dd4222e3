// glTF 2.0 output (.gltf with embedded buffer, or binary .glb) for browser and DCC viewers.
#pragma once

#include <ostream>

#include "export/output_mesh.h"
#include "export/tonemap.h"
#include "hierarchy/hierarchy.h"

namespace rad {

/// Writes one mesh with one triangle primitive: POSITION (float VEC3, with min/max), indices
/// (uint32), COLOR_0 (float VEC3: tone_map(display, tm), display-referred but linear, as glTF
/// vertex colours are), and `_RADIOSITY` (float VEC3: the solver's linear radiosity). Its material
/// is unlit (KHR_materials_unlit), white, single-sided. With textures (OutputMesh::textures), also
/// TEXCOORD_0, each image once as PNG, and a primitive per texture whose unlit material shows it:
/// COLOR_0 is then tone_map(display) / texel x the mesh's extras.colour_scale (1, or less where
/// that would exceed 1), on untextured faces too. Positions are in scene units. `binary`
/// selects GLB; otherwise JSON with the buffer embedded as a data URI. Throws rad::Error when
/// serialisation fails.
void write_gltf(std::ostream& out, const OutputMesh& mesh, const ToneMap& tm, bool binary);

/// Writes the scene itself (rad convert): a node per object of the hierarchy (its name, its
/// children), and on each Pure's node a mesh of its welded triangles (POSITION, uint32 indices)
/// with a material of its own: baseColorFactor the reflectance, emissiveFactor the emission's
/// colour with KHR_materials_emissive_strength its largest channel (when above 1). Positions are
/// placed (world space), so the nodes carry no transforms.
void write_scene_gltf(std::ostream& out, const Hierarchy& h, bool binary);

}  // namespace rad
