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

namespace rad {

namespace {

// Layout: magic, format, fingerprint, payload size, payload checksum, payload. Native byte
// order and float layout: a checkpoint resumes on the machine kind that wrote it.
constexpr char kMagic[8] = {'R', 'A', 'D', 'C', 'K', 'P', 'T', '\n'};
constexpr uint32_t kFormat = 1;
constexpr size_t kHeader = sizeof kMagic + sizeof(uint32_t) + 3 * sizeof(uint64_t);

class Writer {
 public:
  template <typename T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const char*>(&v);
    out.append(p, sizeof v);
  }
  template <typename T>
  void vec(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    pod(uint64_t(v.size()));
    out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  std::string out;
};

class Reader {
 public:
  Reader(const std::string& data, size_t at, const std::string& path)
      : p_(data.data() + at), end_(data.data() + data.size()), path_(path) {}
  template <typename T>
  T pod() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    take(&v, sizeof v);
    return v;
  }
  template <typename T>
  void vec(std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const uint64_t n = pod<uint64_t>();
    // The count is checked against what is left before anything is allocated.
    if (n > uint64_t(end_ - p_) / sizeof(T)) fail("a count exceeds the file");
    v.resize(size_t(n));
    take(v.data(), size_t(n) * sizeof(T));
  }
  bool done() const { return p_ == end_; }
  [[noreturn]] void fail(const std::string& why) const {
    throw Error(SourceLoc{path_}, "corrupt checkpoint: " + why);
  }

 private:
  void take(void* dst, size_t n) {
    if (n > size_t(end_ - p_)) fail("truncated");
    if (n) std::memcpy(dst, p_, n);
    p_ += n;
  }
  const char* p_;
  const char* end_;
  const std::string& path_;
};

void write_lanes(Writer& w, const SampleLanes& l) {
  for (const auto* v : {&l.x, &l.y, &l.z, &l.nx, &l.ny, &l.nz, &l.area, &l.r, &l.g, &l.b})
    w.vec(*v);
}
void read_lanes(Reader& r, SampleLanes& l) {
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
  uint32_t unused = 0;
};
static_assert(sizeof(ShotHeader) == 120 && sizeof(Element) == 20 && sizeof(MeshVertex) == 60);

struct HistoryRecord {
  int64_t shot, source;
  double seconds, unshot_fraction;
};

void write_shot(Writer& w, const ShotSource& s) {
  w.pod(ShotHeader{uint64_t(s.sample_count), s.cluster, s.planar, s.major, s.centroid, s.axis,
                   s.mean_unshot, s.cone_cos, s.cone_sin, s.offset_lo, s.offset_hi, s.area,
                   s.extent, s.near_distance, s.single_distance, s.far_distance, s.box});
  w.vec(s.edge_a), w.vec(s.edge_b), w.vec(s.interior);
  write_lanes(w, s.sample);
  w.vec(s.end_x), w.vec(s.end_y), w.vec(s.end_z);
  write_lanes(w, s.fine_sample);
  w.vec(s.fine_group_parent);
}

ShotSource read_shot(Reader& r, size_t clusters) {
  const auto h = r.pod<ShotHeader>();
  ShotSource s;
  if (h.cluster < 0 || size_t(h.cluster) >= clusters) r.fail("a shot from no cluster");
  s.cluster = h.cluster, s.planar = h.planar != 0, s.major = h.major != 0;
  s.centroid = h.centroid, s.axis = h.axis, s.mean_unshot = h.mean_unshot;
  s.cone_cos = h.cone_cos, s.cone_sin = h.cone_sin, s.offset_lo = h.offset_lo;
  s.offset_hi = h.offset_hi, s.area = h.area, s.extent = h.extent;
  s.near_distance = h.near_distance, s.single_distance = h.single_distance;
  s.far_distance = h.far_distance, s.box = h.box;
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
  return s;
}

void write_polygon(Writer& w, const PolygonMesh& p) {
  w.vec(p.vertices);
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
}

void read_polygon(Reader& r, PolygonMesh& p) {
  r.vec(p.vertices);
  r.vec(p.elements);
  std::vector<uint64_t> keys;
  std::vector<uint32_t> values;
  r.vec(keys);
  r.vec(values);
  if (keys.size() != values.size()) r.fail("unpaired midpoints");
  // The indices the solver follows without checking must be in range.
  const size_t nv = p.vertices.size(), ne = p.elements.size();
  if (nv < 3 || ne < 1) r.fail("a polygon without its triangle");
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
}

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
  }
  for (const SceneObject& ob : h.objects) {
    f.add(ob.kind).add(ob.parent).add(ob.first_triangle).add(ob.triangle_count);
    f.add(ob.material.reflectance).add(ob.material.emission);
    f.add(ob.casts_shadows).add(ob.receives_shadows).add(ob.influence).add(uint64_t(ob.lit.size()));
    for (const TriangleRange& r : ob.lit) f.add(r.first).add(r.count);
  }
  f.add(o.shadows).add(o.sample_grid).add(o.max_sample_grid).add(o.method);
  f.add(o.subdivision_threshold).add(o.midpoints).add(o.min_size).add(o.max_size);
  f.add(o.intensity_cut).add(o.major_shot_fraction).add(o.overshoot).add(backend);
  return f.value();
}

void write_checkpoint(const std::string& path, const SolverState& s, uint64_t fingerprint) {
  static_assert(std::is_trivially_copyable_v<SolverStats>);
  Writer w;
  w.pod(uint64_t(s.mesh.polygons.size()));
  for (const PolygonMesh& p : s.mesh.polygons) write_polygon(w, p);
  w.vec(s.materials);
  w.vec(s.unshot_energy);
  w.pod(s.emitted_energy), w.pod(s.absorbed_energy), w.pod(s.shots), w.pod(s.stats);
  std::vector<HistoryRecord> history;
  for (const ShotRecord& h : s.history)
    history.push_back({h.shot, h.source, h.seconds, h.unshot_fraction});
  w.vec(history);
  w.pod(uint64_t(s.shot_log.size()));
  for (const ShotSource& src : s.shot_log) write_shot(w, src);

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
  Reader r(data, kHeader, path);
  if (r.pod<uint64_t>() != s.mesh.polygons.size()) r.fail("another number of polygons");
  Mesh mesh;
  mesh.polygons.resize(s.mesh.polygons.size());
  for (PolygonMesh& p : mesh.polygons) read_polygon(r, p);
  std::vector<Material> materials;
  std::vector<double> unshot_energy;
  r.vec(materials);
  r.vec(unshot_energy);
  if (materials.size() != s.materials.size() || unshot_energy.size() != s.unshot_energy.size()) {
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
  for (uint64_t i = 0; i < logged; ++i) log.push_back(read_shot(r, s.clusters.size()));
  if (!r.done()) r.fail("trailing bytes");
  if (shots < 0 || uint64_t(shots) != logged) r.fail("shot count differs from the shot log");

  s.mesh = std::move(mesh);
  s.materials = std::move(materials);
  s.unshot_energy = std::move(unshot_energy);
  s.emitted_energy = emitted, s.absorbed_energy = absorbed, s.shots = shots, s.stats = stats;
  s.history = std::move(history);
  s.shot_log = std::move(log);
}

}  // namespace rad
