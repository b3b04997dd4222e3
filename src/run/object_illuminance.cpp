#include "run/object_illuminance.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <numeric>

#include "mesh/subdivide.h"

namespace rad {

namespace {

double luminance(const Vec3& c) {
  return 0.2126 * double(c.x) + 0.7152 * double(c.y) + 0.0722 * double(c.z);
}

}  // namespace

std::vector<ObjectIlluminance> object_illuminance(const SolverState& s, double metres_per_unit) {
  const Hierarchy& h = *s.solution.hierarchy;
  std::vector<ObjectIlluminance> per(h.objects.size());
  for (size_t o = 0; o < per.size(); ++o) {
    per[o].object = int32_t(o), per[o].name = h.objects[o].name;
    per[o].min = std::numeric_limits<double>::infinity();
    per[o].max = -per[o].min;
  }
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
    const std::vector<VertexState>& vs = s.solution.vertex_states[p];
    if (vs.empty()) continue;  // another MPI rank's
    ObjectIlluminance& o = per[size_t(h.triangles.object[p])];
    for (const VertexState& v : vs) {
      const double y = luminance(v.irradiance);
      o.min = std::min(o.min, y), o.max = std::max(o.max, y);
    }
    for_each_leaf_vertex_sum(
        s.solution.mesh.polygons[p], [&](uint32_t v) { return vs[v].irradiance; },
        [&](float area, Vec3 sum) {
          o.mean += double(area) * luminance(sum) / 3.0;
          o.area += double(area);
        });
  }
  std::vector<ObjectIlluminance> out;
  for (ObjectIlluminance& o : per) {
    if (!(o.area > 0.0)) continue;
    o.mean /= o.area;
    o.area *= metres_per_unit * metres_per_unit;
    out.push_back(std::move(o));
  }
  return out;
}

std::string format_illuminance(const std::vector<ObjectIlluminance>& objects, size_t rows) {
  std::vector<size_t> order(objects.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return objects[a].area > objects[b].area; });
  order.resize(std::min(rows, order.size()));
  std::string t = fmt::format(
      "Illuminance (lux with photometric lights), the {} largest of {} "
      "objects:\n",
      order.size(), objects.size());
  t +=
      fmt::format("  {:<28} {:>10} {:>10} {:>10} {:>10}\n", "object", "area", "min", "mean", "max");
  for (size_t i : order) {
    const ObjectIlluminance& o = objects[i];
    const std::string name = o.name.size() > 28 ? o.name.substr(0, 25) + "..." : o.name;
    t += fmt::format("  {:<28} {:>10.4g} {:>10.4g} {:>10.4g} {:>10.4g}\n", name, o.area, o.min,
                     o.mean, o.max);
  }
  return t;
}

}  // namespace rad
