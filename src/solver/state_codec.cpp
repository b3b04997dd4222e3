#include "solver/state_codec.h"

#include <algorithm>
#include <cmath>

#include "solver/light_groups.h"
#include "solver/light_source.h"

namespace rad {

namespace {

void write_lanes(ByteWriter& w, const SampleLanes& l) {
  for (const auto* v : {&l.x, &l.y, &l.z, &l.nx, &l.ny, &l.nz, &l.area, &l.r, &l.g, &l.b})
    w.vec(*v);
}
void read_lanes(ByteReader& r, SampleLanes& l) {
  for (auto* v : {&l.x, &l.y, &l.z, &l.nx, &l.ny, &l.nz, &l.area, &l.r, &l.g, &l.b}) r.vec(*v);
  const size_t n = l.x.size();
  for (const auto* v : {&l.y, &l.z, &l.nx, &l.ny, &l.nz, &l.area, &l.r, &l.g, &l.b}) {
    if (v->size() != n) r.fail("sample lanes of different lengths");
  }
}

// The fixed-size part of a ShotSource, field by field (the struct itself holds vectors).
// Records written whole have no padding, so equal states write equal bytes.
struct ShotHeader {
  uint64_t sample_count;
  int32_t cluster;
  uint32_t planar, major;
  Vec3 centroid, axis, mean_unshot;
  float cone_cos, cone_sin, offset_lo, offset_hi, area, extent;
  float near_distance, single_distance, far_distance;
  Aabb box;
  float roulette_draw, roulette_peak, roulette_reach2;
  int32_t light;  // a light's shot (ShotSource::light): rebuilt from the scene's light
  Vec3 light_colour;
};
static_assert(sizeof(ShotHeader) == 144 && sizeof(Element) == 20 && sizeof(VertexState) == 48);

}  // namespace

void write_shot(ByteWriter& w, const ShotSource& s) {
  w.pod(ShotHeader{uint64_t(s.sample_count),
                   s.cluster,
                   s.planar,
                   s.major,
                   s.centroid,
                   s.axis,
                   s.mean_unshot,
                   s.cone_cos,
                   s.cone_sin,
                   s.offset_lo,
                   s.offset_hi,
                   s.area,
                   s.extent,
                   s.near_distance,
                   s.single_distance,
                   s.far_distance,
                   s.box,
                   s.roulette_draw,
                   s.roulette_peak,
                   s.roulette_reach2,
                   s.light,
                   s.light_colour});
  w.vec(s.edge_a), w.vec(s.edge_b), w.vec(s.interior);
  write_lanes(w, s.sample);
  w.vec(s.end_x), w.vec(s.end_y), w.vec(s.end_z);
  write_lanes(w, s.fine_sample);
  w.vec(s.fine_group_parent);
  w.vec(s.fine_cell_u), w.vec(s.fine_cell_v);
  w.pod(s.light_group);
  w.pod(uint64_t(s.groups.size()));
  for (const GroupShare& g : s.groups) {
    for (const auto* v : {&g.r, &g.g, &g.b, &g.fine_r, &g.fine_g, &g.fine_b}) w.vec(*v);
    w.pod(g.mean_unshot);
  }
}

namespace {

// ShotSource::light_group and ::groups, as write_shot writes them last; their lanes as many
// as the source's.
void read_groups(ByteReader& r, ShotSource& s) {
  s.light_group = r.pod<int32_t>();
  const uint64_t n = r.pod<uint64_t>();
  if (n > kMaxLightGroups) r.fail("more light groups than a scene can hold");
  s.groups.resize(size_t(n));
  for (GroupShare& g : s.groups) {
    for (auto* v : {&g.r, &g.g, &g.b}) {
      r.vec(*v);
      if (v->size() != s.sample.size()) r.fail("a light group's share unlike its samples");
    }
    for (auto* v : {&g.fine_r, &g.fine_g, &g.fine_b}) {
      r.vec(*v);
      if (v->size() != s.fine_sample.size()) r.fail("a light group's share unlike its samples");
    }
    g.mean_unshot = r.pod<Vec3>();
  }
}

}  // namespace

ShotSource read_shot(ByteReader& r, size_t clusters, const std::vector<Light>& lights,
                     const Aabb& bounds) {
  const auto h = r.pod<ShotHeader>();
  if (h.light >= 0) {
    if (size_t(h.light) >= lights.size() || h.cluster != -1) r.fail("a shot from no light");
    if (!std::isfinite(mean_component(h.light_colour))) r.fail("a light's colour not finite");
    ShotSource s = make_light_source(lights, h.light, h.light_colour, bounds);
    // The cluster's parts of the record are empty for a light.
    std::vector<Vec3> none;
    r.vec(none), r.vec(none), r.vec(none);
    SampleLanes lanes;
    read_lanes(r, lanes);
    std::vector<float> ends;
    r.vec(ends), r.vec(ends), r.vec(ends);
    read_lanes(r, lanes);
    std::vector<uint32_t> parents;
    r.vec(parents);
    r.vec(none), r.vec(none);  // the fine points' cells
    ShotSource empty;
    read_groups(r, empty);
    if (!empty.groups.empty()) r.fail("a light's shot with a cluster's light groups");
    s.light_group = empty.light_group;
    return s;
  }
  ShotSource s;
  if (h.cluster < 0 || size_t(h.cluster) >= clusters) r.fail("a shot from no cluster");
  s.cluster = h.cluster, s.planar = h.planar != 0, s.major = h.major != 0;
  s.centroid = h.centroid, s.axis = h.axis, s.mean_unshot = h.mean_unshot;
  s.cone_cos = h.cone_cos, s.cone_sin = h.cone_sin, s.offset_lo = h.offset_lo;
  s.offset_hi = h.offset_hi, s.area = h.area, s.extent = h.extent;
  s.near_distance = h.near_distance, s.single_distance = h.single_distance;
  s.far_distance = h.far_distance, s.box = h.box;
  s.roulette_draw = h.roulette_draw, s.roulette_peak = h.roulette_peak;
  s.roulette_reach2 = h.roulette_reach2;
  if (!(s.roulette_draw >= 0.0f && s.roulette_draw < 1.0f && s.roulette_peak > 0.0f &&
        s.roulette_peak <= 1.0f && s.roulette_reach2 >= 0.0f)) {
    r.fail("a shot's roulette out of range");
  }
  r.vec(s.edge_a), r.vec(s.edge_b), r.vec(s.interior);
  if (s.edge_a.size() != s.edge_b.size()) r.fail("an outline of unpaired edges");
  read_lanes(r, s.sample);
  if (h.sample_count > s.sample.size()) r.fail("more samples than lanes");
  s.sample_count = size_t(h.sample_count);
  r.vec(s.end_x), r.vec(s.end_y), r.vec(s.end_z);
  if (s.end_x.size() < s.sample_count || s.end_y.size() != s.end_x.size() ||
      s.end_z.size() != s.end_x.size()) {
    r.fail("ray ends do not match the samples");
  }
  read_lanes(r, s.fine_sample);
  r.vec(s.fine_group_parent);
  if (s.fine_group_parent.size() * SampleLanes::kLanes != s.fine_sample.size()) {
    r.fail("fine sample groups do not match their lanes");
  }
  for (uint32_t g : s.fine_group_parent) {
    if (g >= s.sample_count) r.fail("a fine sample group of no sample");
  }
  r.vec(s.fine_cell_u), r.vec(s.fine_cell_v);
  if (s.fine_cell_u.size() != s.fine_sample.size() || s.fine_cell_v.size() != s.fine_sample.size())
    r.fail("fine sample cells do not match their lanes");
  read_groups(r, s);
  return s;
}

void write_polygon(ByteWriter& w, const PolygonMesh& p, const std::vector<VertexState>& states,
                   const std::vector<VertexState>& group_states,
                   const std::vector<TextureFactors>& texture_factors,
                   const std::vector<VertexCopy>& copies) {
  w.vec(p.positions);
  w.vec(states);
  w.vec(group_states);
  w.vec(texture_factors);
  w.vec(p.elements);
  // Sorted, so equal states write equal files (the map's order depends on its history).
  std::vector<std::pair<uint64_t, uint32_t>> mids(p.midpoints.entries().begin(),
                                                  p.midpoints.entries().end());
  std::sort(mids.begin(), mids.end());
  std::vector<uint64_t> keys;
  std::vector<uint32_t> values;
  for (const auto& [k, v] : mids) keys.push_back(k), values.push_back(v);
  w.vec(keys);
  w.vec(values);
  w.vec(copies);
}

void read_polygon(ByteReader& r, PolygonMesh& p, std::vector<VertexState>& states,
                  std::vector<VertexState>& group_states,
                  std::vector<TextureFactors>& texture_factors, std::vector<VertexCopy>& copies,
                  size_t polygons, bool textured, size_t group_count) {
  r.vec(p.positions);
  r.vec(states);
  r.vec(group_states);
  r.vec(texture_factors);
  r.vec(p.elements);
  std::vector<uint64_t> keys;
  std::vector<uint32_t> values;
  r.vec(keys);
  r.vec(values);
  if (keys.size() != values.size()) r.fail("unpaired midpoints");
  // The indices the solver follows without checking must be in range.
  const size_t nv = p.positions.size(), ne = p.elements.size();
  if (nv < 3 || ne < 1) r.fail("a polygon without its triangle");
  if (states.size() != nv) r.fail("vertex states not one per vertex");
  if (group_states.size() != nv * group_count)
    r.fail("light groups' vertex states not one per vertex and group");
  if (texture_factors.size() != (textured ? nv : 0))
    r.fail(textured ? "texture factors not one per vertex" : "texture factors of no texture");
  for (size_t e = 0; e < ne; ++e) {
    const Element& el = p.elements[e];
    if (el.v[0] >= nv || el.v[1] >= nv || el.v[2] >= nv) r.fail("an element of no vertex");
    if (!el.leaf() && (size_t(el.first_child) <= e || size_t(el.first_child) + 4 > ne)) {
      r.fail("an element of no children");
    }
  }
  p.midpoints = MidpointMap();
  for (size_t i = 0; i < keys.size(); ++i) {
    if (values[i] >= nv) r.fail("a midpoint of no vertex");
    *p.midpoints.try_emplace(keys[i]).first = values[i];
  }
  r.vec(copies);
  for (size_t i = 0; i < copies.size(); ++i) {
    if (copies[i].vertex >= nv || copies[i].from_polygon >= polygons ||
        (i > 0 && copies[i].vertex <= copies[i - 1].vertex)) {
      r.fail("a copied vertex out of range or order");
    }
  }
}

}  // namespace rad
