// Reader for Geomview OFF polygon files (the `File` geometry of design §2).
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/math.h"

namespace rad {

/// The triangles of an OFF file, faces fan-split in file order.
struct OffTriangles {
  std::vector<std::array<Vec3, 3>> triangles;  // corners a, b, c; front by the right-hand rule
  std::vector<SourceLoc> triangle_locs;        // the line of the face each triangle came from
  size_t vertex_count = 0;
  size_t face_count = 0;
};

/// Parses OFF text. Accepts an optional header keyword `[ST][C][N]OFF` (letters in any order,
/// e.g. OFF, COFF, NOFF, NCOFF, CNOFF, STOFF), then "vertices faces [edges]", one vertex per
/// line (x y z, then normals, colours or texture coordinates, which are ignored), one face per
/// line ("n i0 ... in-1", then an optional colour, ignored). '#' starts a comment. Faces with
/// n > 3 are split into the fan (i0, ik, ik+1). Throws rad::Error at path:line:column for
/// malformed input, non-finite coordinates, out-of-range indices, faces with fewer than three
/// vertices, a file without faces, and the 4OFF / nOFF / BINARY variants.
OffTriangles parse_off_text(std::string_view text, const std::string& path);

/// Reads and parses the OFF file at `path`. Errors about opening it are located at
/// `requested_at` (the `File` token that named it); errors in its content at the file itself.
OffTriangles read_off_file(const std::string& path, const SourceLoc& requested_at);

}  // namespace rad
