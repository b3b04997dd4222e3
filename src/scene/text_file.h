// Reading a whole input file (a description or an OFF file) into memory.
#pragma once

#include <string>

#include "core/error.h"

namespace rad {

/// Returns the bytes of the regular file at `path`. Throws rad::Error located at `requested_at`
/// (the token that named the file; or just the path when there is none) if it is missing, not a
/// regular file or unreadable.
std::string read_text_file(const std::string& path, const SourceLoc& requested_at);

}  // namespace rad
