#include <fmt/format.h>

#include "core/error.h"
#include "visibility/backend.h"
#include "visibility/brute_backend.h"
#include "visibility/embree_backend.h"
#include "visibility/grid_backend.h"
#include "visibility/occluders.h"

namespace rad {

const char* to_string(BackendKind kind) {
  switch (kind) {
    case BackendKind::Embree:
      return "embree";
    case BackendKind::Grid:
      return "grid";
    case BackendKind::Brute:
      return "brute";
  }
  return "?";
}

BackendKind parse_backend_kind(std::string_view name) {
  if (name == "embree") return BackendKind::Embree;
  if (name == "grid") return BackendKind::Grid;
  if (name == "brute") return BackendKind::Brute;
  throw Error(
      fmt::format("unknown visibility backend \"{}\" (expected embree, grid or brute)", name));
}

std::unique_ptr<VisibilityBackend> make_visibility_backend(BackendKind kind, const Hierarchy& h,
                                                           const VisibilityOptions& options) {
  // Every backend traces against the same merged surfaces (none keeps the hierarchy after
  // its build), so they agree exactly, and a tessellated wall costs them what the wall does.
  const std::optional<Hierarchy> merged = merge_flat_regions(h);
  const Hierarchy& occluders = merged ? *merged : h;
  switch (kind) {
    case BackendKind::Embree:
      return make_embree_backend(occluders, options);
    case BackendKind::Grid:
      return make_grid_backend(occluders, options);
    case BackendKind::Brute:
      return make_brute_backend(occluders, options);
  }
  throw Error("unknown visibility backend");
}

}  // namespace rad
