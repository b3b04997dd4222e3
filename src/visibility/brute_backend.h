// The brute-force visibility backend: every segment against every triangle (reference, tests).
#pragma once

#include <memory>

#include "visibility/backend.h"

namespace rad {

/// Tests each segment against all triangles of the hierarchy with the design §6 test
/// (segment_hits_triangle), stopping at the first hit. O(rays × triangles): the reference the
/// other backends are checked against, and fine for tiny scenes. Thread-safe.
std::unique_ptr<VisibilityBackend> make_brute_backend(const Hierarchy& h,
                                                      const VisibilityOptions& options);

}  // namespace rad
