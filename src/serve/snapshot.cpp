#include "serve/snapshot.h"

namespace rad {

const char* to_string(SessionStatus s) {
  switch (s) {
    case SessionStatus::Running:
      return "running";
    case SessionStatus::Paused:
      return "paused";
    case SessionStatus::Converged:
      return "converged";
    case SessionStatus::Stopped:
      return "stopped";
  }
  return "?";
}

std::vector<int64_t> elements_per_object(const SolverState& s) {
  const Hierarchy& h = *s.solution.hierarchy;
  std::vector<int64_t> prefix(s.solution.mesh.polygons.size() + 1, 0);
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
    int64_t n = 0;
    for_each_leaf(s.solution.mesh.polygons[p], [&](uint32_t) { ++n; });
    prefix[p + 1] = prefix[p] + n;
  }
  std::vector<int64_t> out(h.objects.size(), 0);
  for (size_t o = 0; o < h.objects.size(); ++o) {
    const SceneObject& obj = h.objects[o];
    out[o] = prefix[obj.first_triangle + obj.triangle_count] - prefix[obj.first_triangle];
  }
  return out;
}

std::vector<std::pair<int64_t, double>> thin_history(const std::vector<ShotRecord>& h,
                                                     size_t limit) {
  std::vector<std::pair<int64_t, double>> out;
  if (h.empty() || limit == 0) return out;
  const size_t stride = (h.size() + limit - 1) / limit;
  for (size_t i = 0; i < h.size(); i += stride) out.emplace_back(h[i].shot, h[i].unshot_fraction);
  if (out.back().first != h.back().shot) {
    if (out.size() == limit) out.pop_back();
    out.emplace_back(h.back().shot, h.back().unshot_fraction);
  }
  return out;
}

}  // namespace rad
