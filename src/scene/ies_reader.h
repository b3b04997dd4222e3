// Reader of IES LM-63 photometric files (`.ies`: LM-63-1986, -1991, -1995 and -2002), type C.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "core/error.h"
#include "scene/photometry.h"

namespace rad {

/// Parses the text of an IES LM-63 file: its header (an optional IESNA line and keyword or
/// free-text lines) up to the TILT= line, then the numbers, separated by blanks or commas: lamps,
/// lumens per lamp (-1: absolute photometry), candela multiplier, vertical and horizontal angle
/// counts, photometric type (1 = C; types A and B are refused), units, width, length, height,
/// ballast factor, ballast-lamp (future use) factor, input watts, the vertical angles, the
/// horizontal angles, and the candela values (one run of vertical values per horizontal angle).
/// TILT=INCLUDE data and TILT=<file> are read past with a warning (the tilt factors are not
/// applied). Throws one rad::Error naming path:line:column for anything malformed: a missing
/// TILT line, a non-number, a count out of range, angles not increasing or outside type C's
/// ranges, a negative candela value, a truncated table or values after it. `path` names the text
/// in errors and in the result.
Photometry parse_ies(std::string_view text, const std::string& path);

/// Reads and parses the file at `path`. Errors opening it are located at `requested_at` (the
/// token that named it), errors in it at the file.
std::shared_ptr<const Photometry> read_ies_file(const std::string& path,
                                                const SourceLoc& requested_at);

}  // namespace rad
