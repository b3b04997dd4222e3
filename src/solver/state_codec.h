// The solver's records as bytes: a shot source and a polygon's mesh, for the checkpoint file
// and for the messages between MPI ranks. Native byte order and float layout; equal records
// write equal bytes.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.h"
#include "mesh/patch_mesh.h"
#include "solver/shot_source.h"
#include "solver/solver_state.h"

namespace rad {

class ByteWriter {
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

class ByteReader {
 public:
  /// Reads `data` from byte `at`; errors name `origin` (a file, a rank) and say what is
  /// corrupt: "corrupt <what>: <why>".
  ByteReader(const std::string& data, size_t at, std::string origin, std::string what)
      : p_(data.data() + at),
        end_(data.data() + data.size()),
        origin_(std::move(origin)),
        what_(std::move(what)) {}
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
    throw Error(SourceLoc{origin_}, "corrupt " + what_ + ": " + why);
  }

 private:
  void take(void* dst, size_t n) {
    if (n > size_t(end_ - p_)) fail("truncated");
    if (n) std::memcpy(dst, p_, n);
    p_ += n;
  }
  const char* p_;
  const char* end_;
  std::string origin_, what_;
};

void write_shot(ByteWriter& w, const ShotSource& s);
/// Throws rad::Error when the record is inconsistent; `clusters` bounds its cluster index.
ShotSource read_shot(ByteReader& r, size_t clusters, const std::vector<Light>& lights,
                     const Aabb& bounds);

/// A polygon's mesh, its vertex states and its light groups' (solution.h), its texture factors
/// and its vertices that copy another's gain (solver_state.h).
void write_polygon(ByteWriter& w, const PolygonMesh& p, const std::vector<VertexState>& states,
                   const std::vector<VertexState>& group_states,
                   const std::vector<TextureFactors>& texture_factors,
                   const std::vector<VertexCopy>& copies);
/// Throws rad::Error when an index of the record is out of range, `textured` differs from
/// whether it has texture factors, or its light groups' states are not `group_count` per vertex
/// (a copy's vertex in the polygon it copies from is the caller's to check, once every polygon
/// is read).
void read_polygon(ByteReader& r, PolygonMesh& p, std::vector<VertexState>& states,
                  std::vector<VertexState>& group_states,
                  std::vector<TextureFactors>& texture_factors, std::vector<VertexCopy>& copies,
                  size_t polygons, bool textured, size_t group_count);

}  // namespace rad
