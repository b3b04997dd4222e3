#include "solver/shoot.h"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "mesh/subdivide.h"
#include "solver/light_source.h"
#include "solver/refine.h"

namespace rad {

GatherSettings gather_settings(const SolverOptions& options, const SceneCaches& scene,
                               const EnergyBalance& energy) {
  GatherSettings g;
  g.method = options.method;
  g.shadows = options.shadows;
  g.cut = options.intensity_cut * energy.radiosity_scale;
  g.shadow_offset = scene.shadow_offset;
  g.penumbra_rays = uint32_t(std::max(0, options.penumbra_rays));
  g.penumbra_sample_energy = SolverOptions::kPenumbraSampleShare * energy.reference_energy;
  return g;
}

GatherSettings receiver_settings(const GatherSettings& g, const Hierarchy& h, size_t p) {
  GatherSettings r = g;
  r.shadows = g.shadows && h.objects[size_t(h.triangles.object[p])].receives_shadows;
  return r;
}

int32_t shooter_influence(const Hierarchy& h, const Clusters& clusters, const ShotSource& src) {
  if (src.light >= 0) return -1;  // a light lights everything
  const uint32_t p = clusters.polygons[clusters.first[size_t(src.cluster)]];
  return h.objects[size_t(h.triangles.object[p])].influence;
}

bool may_receive(const Hierarchy& h, const Clusters& clusters, size_t p, const ShotSource& src) {
  const Triangles& t = h.triangles;
  if (src.light >= 0) return light_reaches(src, t.corners[p], t.normal[p]);
  if (src.planar && clusters.cluster_of[p] == uint32_t(src.cluster)) return false;
  if (!influence_reaches(h, shooter_influence(h, clusters, src), uint32_t(p))) return false;
  const auto& c = t.corners[p];
  bool any_in_front = false;
  for (const Vec3& q : c) any_in_front |= receiver_side(src, q) >= 0;
  if (!any_in_front) return false;
  // The source's box against p's plane: its farthest corner in front.
  return highest_above(src.box, c[0], t.normal[p]) > 0.0f;
}

namespace {
// After a major shot, the leaves of its receivers whose middle the shot lights more than their
// corners say (Receivers::bright_middles). Refinement looks at vertices only: the front of a
// fryer's base, 22 cm wide, its three corners in dark nooks (under the body, by the table top)
// and its middle open to the room, reads the dark at all three and never splits, and the light
// that reaches its middle is never shot on. A leaf's centroid gathers the shot once; where the
// gain there, weighed by the material's reflectance, exceeds its corners' mean by more than the
// subdivision limit, the leaf splits as if its corners differed. Light that varies linearly
// across a leaf is its corners' mean at the centroid: only what the corners miss splits. A
// middle darker than its corners (inside a solid the leaf crosses, in a small shadow) is left
// to the other rules (docs/solver.md, "Bright middles").
void find_bright_middles(ShotContext ctx, const ShotSource& src, const VisibilityBackend& vis,
                         const GatherSettings& settings) {
  const Hierarchy& h = *ctx.solution.hierarchy;
  const Triangles& tris = h.triangles;
  const float limit = subdivision_limit(ctx.options, ctx.energy);
  const float min_split = min_split_size(ctx.scene);
  // The leaves to look at, as work items (a polygon may hold most of them: the Cornell box's
  // floor), then their answers.
  std::vector<LeafRef>& work = ctx.receivers.middle_work;
  work.clear();
  for (const uint32_t p : ctx.receivers.polygons) {
    const PolygonMesh& mesh = ctx.solution.mesh.polygons[p];
    for_each_leaf(mesh, [&](uint32_t e) {
      if (split_size(mesh, e) >= min_split) work.push_back({p, e});
    });
  }
  std::vector<uint8_t>& is_bright = ctx.receivers.middle_bright;
  is_bright.assign(work.size(), 0);
  parallel_gather(work.size(), 64, ctx.stats, [&](size_t begin, size_t end, GatherScratch& sc) {
    for (size_t i = begin; i != end; ++i) {
      const uint32_t p = work[i].polygon;
      const PolygonMesh& mesh = ctx.solution.mesh.polygons[p];
      const std::vector<VertexState>& vs = ctx.solution.vertex_states[p];
      const Vec3 n = tris.normal[p], centroid = tris.centroid(p);
      const Vec3 rho = ctx.solution.material_of(p).reflectance;
      const GatherSettings own = receiver_settings(settings, h, p);
      GatherSettings clear = own;
      clear.shadows = false;
      const Element& el = mesh.elements[work[i].element];
      const Vec3 mid =
          (mesh.positions[el.v[0]] + mesh.positions[el.v[1]] + mesh.positions[el.v[2]]) *
          (1.0f / 3.0f);
      const Vec3 corners =
          (vs[el.v[0]].last_gain + vs[el.v[1]].last_gain + vs[el.v[2]].last_gain) * (1.0f / 3.0f);
      auto bright = [&](const Vec3& gain) { return max_component(rho * (gain - corners)) > limit; };
      // Its rays only when the middle, every ray clear, would be bright: most are not.
      ++sc.stats.middles;
      if (!bright(gather_from_source(mid, n, centroid, src, vis, clear, sc))) continue;
      if (!own.shadows) {  // the gain with every ray clear is the answer
        is_bright[i] = 1;
        continue;
      }
      ++sc.stats.middles;
      is_bright[i] = bright(gather_from_source(mid, n, centroid, src, vis, own, sc));
    }
  });
  // In polygon order, each polygon's leaves in the walk's order: sorted after.
  std::vector<LeafRef>& out = ctx.receivers.bright_middles;
  for (size_t i = 0; i < work.size(); ++i)
    if (is_bright[i]) out.push_back(work[i]);
  std::sort(out.begin(), out.end());
}
}  // namespace

const Receivers& shoot_to_receivers(ShotContext ctx, const ShotSource& src,
                                    const VisibilityBackend& vis, bool major) {
  const Hierarchy& h = *ctx.solution.hierarchy;
  const Triangles& tris = h.triangles;
  const GatherSettings settings = gather_settings(ctx.options, ctx.scene, ctx.energy);
  const float reach = shooting_reach(ctx.scene);
  const SharedVertices& shared = ctx.scene.shared;
  // The mask is kept between shots and cleared where the last shot set it: a shot that reaches
  // a few rooms of a building costs those rooms, not a pass over the whole scene.
  std::vector<uint8_t>& received = ctx.receivers.marked;
  std::vector<uint32_t>& receivers = ctx.receivers.polygons;
  ctx.receivers.bright_middles.clear();
  if (received.size() != tris.size()) {
    received.assign(tris.size(), 0);
  } else {
    for (uint32_t p : receivers) received[p] = 0;
  }
  receivers.clear();
  // With a Lights list only the triangles it names are looked at; under MPI, only this rank's.
  const int32_t influence = shooter_influence(h, ctx.scene.clusters, src);
  // The candidates: a Lights list's ranges, or the triangles not hidden behind a flat occluder
  // (occlusion_culling.h; built only when culling is on), or all.
  // The sun is not culled: it lies beyond the planes of all occluders, in no box.
  const bool sun = src.light >= 0 && src.emitter->kind == LightKind::Directional;
  std::vector<TriangleRange> ranges{{0, uint32_t(tris.size())}};
  const std::vector<uint32_t>* listed = nullptr;
  if (influence >= 0) {
    ranges = h.objects[size_t(influence)].lit;
  } else if (!ctx.scene.culling.empty() && !sun) {
    unhidden_triangles(ctx.scene.culling, src, ctx.receivers.unhidden);
    ctx.stats.hidden += tris.size() - ctx.receivers.unhidden.size();
    listed = &ctx.receivers.unhidden;
  }
  auto consider = [&](size_t n, auto&& triangle) {
    tbb::parallel_for(size_t(0), n, [&](size_t i) {
      const size_t p = triangle(i);
      received[p] = ctx.ownership.owns(p) && may_receive(h, ctx.scene.clusters, p, src) &&
                    src.roulette_reaches_triangle(triangle_box(tris.corners[p]), tris.corners[p][0],
                                                  tris.normal[p]);
    });
    for (size_t i = 0; i < n; ++i)
      if (received[triangle(i)]) receivers.push_back(uint32_t(triangle(i)));
  };
  if (listed) {
    consider(listed->size(), [&](size_t i) { return size_t((*listed)[i]); });
  } else {
    for (const TriangleRange& r : ranges)
      consider(r.count, [&](size_t i) { return size_t(r.first) + i; });
  }
  // Work items: a polygon's vertices, or 64 of them for a finely subdivided one, so its
  // vertices spread across threads too.
  std::vector<VertexRange>& work = ctx.receivers.gather_work;
  work.clear();
  for (size_t i = 0; i < receivers.size(); ++i) {
    const uint32_t p = receivers[i];
    const uint32_t nv = uint32_t(ctx.solution.mesh.polygons[p].vertex_count());
    const uint32_t step = nv < 256 ? nv : 64;
    for (uint32_t v = 0; v < nv; v += step) {
      work.push_back({p, v, std::min(nv, v + step), uint32_t(i)});
    }
  }
  // A light shoots once: nothing to keep its answers for.
  KeptRays* const kept =
      src.light >= 0 ? nullptr
                     : prepare_kept_rays(ctx.kept, src, uint64_t(ctx.shots.count) + 1, receivers,
                                         ctx.solution.mesh, ctx.scene.clusters.size(),
                                         ctx.options.kept_rays_bytes);
  const size_t groups = ctx.solution.group_count;
  parallel_gather(work.size(), 1, ctx.stats, [&](size_t begin, size_t end, GatherScratch& sc) {
    const std::span<Vec3> group_gain = group_gains(sc, groups);
    for (size_t i = begin; i != end; ++i) {
      const VertexRange& w = work[i];
      const uint32_t p = w.polygon;
      const PolygonMesh& mesh = ctx.solution.mesh.polygons[p];
      std::vector<VertexState>& vs = ctx.solution.vertex_states[p];
      const Vec3 n = tris.normal[p], centroid = tris.centroid(p);
      const Vec3 rho = ctx.solution.material_of(p).reflectance;
      const std::vector<TextureFactors>& factors = ctx.solution.texture_factors[p];
      const GatherSettings own = receiver_settings(settings, h, p);
      // A shared vertex is skipped when the one that gathers for it is in a received polygon.
      const std::vector<VertexCopy>& copies = shared.copies[p];
      auto next = std::lower_bound(copies.begin(), copies.end(), w.begin,
                                   [](const VertexCopy& x, uint32_t v) { return x.vertex < v; });
      for (uint32_t v = w.begin; v < w.end; ++v) {
        if (next != copies.end() && next->vertex == v) {
          if (received[next++->from_polygon]) continue;
        }
        VertexState& x = vs[v];
        const VertexRays rays = kept ? vertex_rays(*kept, w.receiver, v) : VertexRays{};
        const Vec3 at = ctx.scene.buried.gather_point(p, v, mesh.positions[v]);
        const Vec3 dh = gather_from_source(at, n, centroid, src, vis, own, sc,
                                           kept ? &rays : nullptr, group_gain);
        const Vec3 rho_v = factors.empty() ? rho : rho * factors[v].reflectance;
        const bool shoots = shoots_from(mesh.positions[v], at, reach);
        x.receive(dh, rho_v, major, shoots);
        for (size_t g = 0; g < groups; ++g) {
          ctx.solution.group_states[p][v * groups + g].receive(group_gain[g], rho_v, major, shoots);
        }
      }
    }
  });
  // The shared vertices take the gain of the one that gathered for them, and reflect it by
  // their own reflectance (the same Pure's, but each polygon's texture coordinates).
  tbb::parallel_for(size_t(0), receivers.size(), [&](size_t i) {
    const uint32_t p = receivers[i];
    std::vector<VertexState>& vs = ctx.solution.vertex_states[p];
    for (const VertexCopy& copy : shared.copies[p]) {
      if (!received[copy.from_polygon]) continue;
      const Vec3 dh = ctx.solution.vertex_states[copy.from_polygon][copy.from_vertex].last_gain;
      // Whether it shoots is the copy's own (each polygon probes toward its own centroid, so a
      // shared vertex may be buried for one and not the other): what refinement reads back.
      const Vec3 rho = ctx.solution.reflectance(p, copy.vertex);
      const bool shoots = ctx.scene.buried.shoots(
          p, copy.vertex, ctx.solution.mesh.polygons[p].positions[copy.vertex], reach);
      vs[copy.vertex].receive(dh, rho, major, shoots);
      for (size_t g = 0; g < groups; ++g) {
        const size_t from = size_t(copy.from_vertex) * groups + g;
        ctx.solution.group_states[p][size_t(copy.vertex) * groups + g].receive(
            ctx.solution.group_states[copy.from_polygon][from].last_gain, rho, major, shoots);
      }
    }
  });
  // A shot that takes light away (an edit dimming a light or a material) darkens a middle its
  // corners miss, and its gain with every ray clear is no bound: no look.
  const Vec3 shot_colour = src.light >= 0 ? src.light_colour : src.mean_unshot;
  if (major && std::min({shot_colour.x, shot_colour.y, shot_colour.z}) >= 0.0f)
    find_bright_middles(ctx, src, vis, settings);
  return ctx.receivers;
}

}  // namespace rad
