// The Embree visibility backend (default): one Embree BVH over the scene's world triangles.
#pragma once

#include <memory>

#include "visibility/backend.h"

namespace rad {

/// Builds one Embree 3 scene with a triangle geometry per Pure over the flattened world-space
/// triangles. With options.packets, batches are traced as coherent 16-ray packets
/// (rtcOccluded16), else one rtcOccluded1 per segment; the answers are the same. Throws rad::Error
/// on any Embree error during construction. Thread-safe; sets FTZ/DAZ on the calling thread for
/// the duration of each call, as Embree requires.
std::unique_ptr<VisibilityBackend> make_embree_backend(const Hierarchy& h,
                                                       const VisibilityOptions& options);

}  // namespace rad
