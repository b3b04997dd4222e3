#include "solver/checkpoint.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <type_traits>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/fingerprint.h"
#include "solver/state_codec.h"
#include "solver/texture_factors.h"

namespace rad {

namespace {

// Layout: magic, format, fingerprint, payload size, payload checksum, payload. Native byte
// order and float layout: a checkpoint resumes on the machine kind that wrote it.
constexpr char kMagic[8] = {'R', 'A', 'D', 'C', 'K', 'P', 'T', '\n'};
// The payload's layout version: a checkpoint of another layout is refused.
constexpr uint32_t kFormat = 12;
constexpr size_t kHeader = sizeof kMagic + sizeof(uint32_t) + 3 * sizeof(uint64_t);

struct HistoryRecord {
  int64_t shot, source;
  double seconds, unshot_fraction;
};

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(SourceLoc{path}, "cannot read the checkpoint");
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

uint64_t solve_fingerprint(const Hierarchy& h, const SolverOptions& o, BackendKind backend) {
  Fingerprint f;
  f.add(kFormat).add(uint64_t(h.triangles.size()));
  for (size_t t = 0; t < h.triangles.size(); ++t) {
    f.add(h.triangles.corners[t]).add(h.triangles.object[t]);
    if (!h.triangles.uv.empty()) f.add(h.triangles.uv[t]);
  }
  for (const SceneObject& ob : h.objects) {
    f.add(ob.kind).add(ob.parent).add(ob.first_triangle).add(ob.triangle_count);
    f.add(ob.material.reflectance).add(ob.material.emission);
    // A texture by its name, size and mean: another image is another solve.
    f.add(bool(ob.base_texture));
    if (const TextureMap& t = ob.base_texture) {
      f.add(std::string_view(t.image->name))
          .add(t.image->file_width)
          .add(t.image->file_height)
          .add(t.image->mean);
      f.add(t.sampler.wrap_s).add(t.sampler.wrap_t).add(t.sampler.nearest);
    }
    f.add(bool(ob.emissive_texture));
    if (const TextureMap& t = ob.emissive_texture) {
      f.add(std::string_view(t.image->name)).add(t.image->mean);
      f.add(t.sampler.wrap_s).add(t.sampler.wrap_t).add(t.sampler.nearest);
    }
    f.add(bool(ob.cutout));
    if (const AlphaMask& m = ob.cutout) {
      f.add(std::string_view(m.texture.image->name)).add(m.texture.image->mean);
      f.add(m.from_red).add(m.scale).add(m.cutoff).add(m.texture.sampler.wrap_s);
      f.add(m.texture.sampler.wrap_t).add(m.texture.sampler.nearest);
    }
    f.add(ob.casts_shadows).add(ob.receives_shadows).add(ob.influence).add(uint64_t(ob.lit.size()));
    for (const TriangleRange& r : ob.lit) f.add(r.first).add(r.count);
  }
  f.add(uint64_t(h.lights.size()));
  for (const Light& l : h.lights) {
    f.add(l.kind).add(l.position).add(l.direction).add(l.colour).add(l.intensity);
    f.add(l.inner_cone).add(l.outer_cone).add(l.angular_diameter).add(l.photometric_up);
    // An IES table by its values: another file, or the same file changed, is another solve.
    f.add(l.photometry != nullptr);
    if (l.photometry) {
      const Photometry& p = *l.photometry;
      for (const std::vector<float>* v : {&p.vertical, &p.horizontal, &p.candela})
        f.add(uint64_t(v->size())).bytes(v->data(), v->size() * sizeof(float));
    }
  }
  // The light groups: which emitter is in which is another split of the same light.
  for (const SceneObject& ob : h.objects) f.add(std::string_view(ob.group));
  for (const Light& l : h.lights) f.add(std::string_view(l.group));
  f.add(o.shadows).add(o.sample_grid).add(o.max_sample_grid).add(o.method);
  f.add(o.subdivision_threshold).add(o.midpoints).add(o.min_size).add(o.max_size);
  f.add(o.intensity_cut)
      .add(o.roulette)
      .add(o.major_shot_fraction)
      .add(o.overshoot)
      .add(o.occlusion_culling)
      .add(backend);
  // Only when on: a checkpoint written without penumbra rays stays valid.
  if (o.penumbra_rays != 0) f.add(std::string_view("penumbra rays")).add(o.penumbra_rays);
  return f.value();
}

void write_checkpoint(const std::string& path, const SolverState& s, uint64_t fingerprint) {
  static_assert(std::is_trivially_copyable_v<SolverStats>);
  ByteWriter w;
  w.pod(uint64_t(s.solution.mesh.polygons.size()));
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p)
    write_polygon(w, s.solution.mesh.polygons[p], s.solution.vertex_states[p],
                  s.solution.group_states_of(p), s.solution.texture_factors[p],
                  s.scene.shared.copies[p]);
  w.vec(s.solution.materials);
  w.vec(s.energy.unshot_energy);
  w.pod(s.energy.emitted_energy), w.pod(s.energy.absorbed_energy), w.pod(s.shots.count),
      w.pod(s.stats);
  std::vector<HistoryRecord> history;
  for (const ShotRecord& h : s.shots.history)
    history.push_back({h.shot, h.source, h.seconds, h.unshot_fraction});
  w.vec(history);
  w.pod(uint64_t(s.shots.sources.size()));
  for (const ShotSource& src : s.shots.sources) write_shot(w, src);
  w.vec(s.shots.cluster_cost);
  w.vec(s.energy.cluster_balance);
  w.vec(s.energy.light_unshot);

  const uint64_t checksum = Fingerprint().bytes(w.out.data(), w.out.size()).value();
  AtomicFile f(path);
  f.make_durable();
  auto& o = f.stream();
  o.write(kMagic, sizeof kMagic);
  o.write(reinterpret_cast<const char*>(&kFormat), sizeof kFormat);
  const uint64_t header[3] = {fingerprint, uint64_t(w.out.size()), checksum};
  o.write(reinterpret_cast<const char*>(header), sizeof header);
  o.write(w.out.data(), std::streamsize(w.out.size()));
  f.commit();
}

void read_checkpoint(const std::string& path, SolverState& s, uint64_t fingerprint) {
  // Kept shadow-ray answers belong to the mesh being replaced.
  s.kept.clusters.clear();
  s.kept.bytes = 0;
  s.kept.last_shot.clear();
  const std::string data = read_file(path);
  if (data.size() < kHeader || std::memcmp(data.data(), kMagic, sizeof kMagic) != 0) {
    throw Error(SourceLoc{path}, "not a rad checkpoint");
  }
  uint32_t format = 0;
  uint64_t header[3];
  std::memcpy(&format, data.data() + sizeof kMagic, sizeof format);
  std::memcpy(header, data.data() + sizeof kMagic + sizeof format, sizeof header);
  if (format != kFormat) {
    throw Error(SourceLoc{path}, fmt::format("checkpoint format {} (this rad reads {}); remove "
                                             "it to start again",
                                             format, kFormat));
  }
  if (header[1] != data.size() - kHeader ||
      Fingerprint().bytes(data.data() + kHeader, data.size() - kHeader).value() != header[2]) {
    throw Error(SourceLoc{path},
                "corrupt checkpoint: its checksum does not match (torn or "
                "damaged file); remove it to start again");
  }
  if (header[0] != fingerprint) {
    throw Error(SourceLoc{path},
                "checkpoint of another solve: the scene, the solver options or the backend "
                "differ from the run that wrote it; remove it or pass another --checkpoint");
  }

  // Read everything into a copy, so a failure leaves `s` as it was.
  ByteReader r(data, kHeader, path, "checkpoint");
  if (r.pod<uint64_t>() != s.solution.mesh.polygons.size()) r.fail("another number of polygons");
  const size_t np = s.solution.mesh.polygons.size();
  Mesh mesh;
  mesh.polygons.resize(np);
  std::vector<std::vector<VertexState>> states(np), group_states(np);
  std::vector<std::vector<VertexCopy>> copies(np);
  std::vector<std::vector<TextureFactors>> factors(np);
  for (size_t p = 0; p < np; ++p) {
    read_polygon(r, mesh.polygons[p], states[p], group_states[p], factors[p], copies[p], np,
                 is_textured(s.solution.hierarchy->triangles, p, s.solution.object_of(p)),
                 s.solution.group_count);
  }
  // A copy's source gathers: it is a vertex, and no copy itself (a chain would have the shot
  // read a gain while another thread writes it).
  SharedVertices shared;
  shared.copies = std::move(copies);
  for (const std::vector<VertexCopy>& cs : shared.copies) {
    for (const VertexCopy& c : cs) {
      if (c.from_vertex >= mesh.polygons[c.from_polygon].vertex_count() ||
          shared.is_copy(c.from_polygon, c.from_vertex)) {
        r.fail("a vertex copied from no vertex, or from a copy");
      }
    }
  }
  std::vector<Material> materials;
  std::vector<UnshotEnergy> unshot_energy;
  r.vec(materials);
  r.vec(unshot_energy);
  if (materials.size() != s.solution.materials.size() ||
      unshot_energy.size() != s.energy.unshot_energy.size()) {
    r.fail("another number of materials or polygons");
  }
  const auto emitted = r.pod<double>(), absorbed = r.pod<double>();
  const auto shots = r.pod<int64_t>();
  const auto stats = r.pod<SolverStats>();
  std::vector<HistoryRecord> records;
  r.vec(records);
  std::vector<ShotRecord> history;
  for (const HistoryRecord& h : records) {
    history.push_back({h.shot, int32_t(h.source), h.seconds, h.unshot_fraction});
  }
  const auto logged = r.pod<uint64_t>();
  std::vector<ShotSource> log;
  const size_t groups = s.solution.group_count;
  for (uint64_t i = 0; i < logged; ++i) {
    log.push_back(read_shot(r, s.scene.clusters.size(), s.scene.shooting_lights,
                            s.solution.hierarchy->bounds));
    // The gather indexes the groups by these without checking them.
    const ShotSource& k = log.back();
    const int32_t light_group =
        k.light >= 0 && groups > 0 ? int32_t(s.solution.light_group[size_t(k.light)]) : -1;
    if (k.light_group != light_group || k.groups.size() != (k.light >= 0 ? 0 : groups))
      r.fail("a logged shot of other light groups");
  }
  std::vector<double> cluster_cost;
  r.vec(cluster_cost);
  if (cluster_cost.size() > s.scene.clusters.size()) r.fail("more shot costs than clusters");
  std::vector<ShotBalance> balance;
  r.vec(balance);
  if (balance.size() > s.scene.clusters.size()) r.fail("more shot balances than clusters");
  std::vector<Vec3> light_unshot;
  r.vec(light_unshot);
  if (light_unshot.size() != s.energy.light_unshot.size()) r.fail("another number of lights");
  if (!r.done()) r.fail("trailing bytes");
  if (shots < 0 || uint64_t(shots) < logged) r.fail("more shots logged than made");

  std::vector<uint32_t> initial(np);
  for (size_t p = 0; p < np; ++p) initial[p] = uint32_t(s.solution.mesh.polygons[p].vertex_count());
  s.solution.mesh = std::move(mesh);
  s.solution.vertex_states = std::move(states);
  if (s.solution.group_count > 0) s.solution.group_states = std::move(group_states);
  s.solution.texture_factors = std::move(factors);
  s.scene.shared.copies = std::move(shared.copies);
  find_edge_midpoints(s.scene.shared, s.solution.mesh, s.solution.hierarchy->triangles,
                      s.scene.clusters, initial);
  s.solution.materials = std::move(materials);
  s.energy.unshot_energy = std::move(unshot_energy);
  s.energy.emitted_energy = emitted, s.energy.absorbed_energy = absorbed, s.shots.count = shots,
  s.stats = stats;
  s.energy.reference_energy = emitted;  // a checkpoint is of a run without edits
  s.shots.history = std::move(history);
  s.shots.sources = std::move(log);
  s.shots.cluster_cost = std::move(cluster_cost);
  s.energy.cluster_retention.clear();
  for (const ShotBalance& b : balance) s.energy.cluster_retention.push_back(b.retention());
  s.energy.cluster_balance = std::move(balance);
  s.energy.light_unshot = std::move(light_unshot);
  update_unshot_totals(s.energy, s.solution, s.scene.clusters, s.ownership.ranks);
}

}  // namespace rad
