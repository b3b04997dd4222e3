#include "reference/reference_set.h"

#include <fmt/format.h>

#include <fstream>
#include <istream>
#include <ostream>
#include <sstream>

#include "core/error.h"

namespace rad {

namespace {
constexpr const char* kHeader = "triangle,u,v,x,y,z,B_r,B_g,B_b,stderr_r,stderr_g,stderr_b";
}  // namespace

void write_reference_csv(std::ostream& out, const ReferenceSet& set) {
  for (const std::string& c : set.comments) out << "# " << c << "\n";
  out << kHeader << "\n";
  for (size_t i = 0; i < set.points.size(); ++i) {
    const ReferencePoint& p = set.points[i];
    const ReferenceValue& r = set.values[i];
    out << fmt::format(
        "{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.7g},{:.7g},{:.7g},{:.3g},{:.3g},{:.3g}\n",
        p.triangle, p.u, p.v, p.position.x, p.position.y, p.position.z, r.radiosity.x,
        r.radiosity.y, r.radiosity.z, r.standard_error.x, r.standard_error.y, r.standard_error.z);
  }
}

ReferenceSet read_reference_csv(std::istream& in, const std::string& name) {
  ReferenceSet set;
  std::string line;
  int line_no = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line[0] == '#') {
      set.comments.push_back(line.size() > 2 ? line.substr(2) : std::string());
      continue;
    }
    if (!header) {
      if (line != kHeader) {
        throw Error(SourceLoc{name, line_no, 1}, fmt::format("expected the header '{}'", kHeader));
      }
      header = true;
      continue;
    }
    std::istringstream row(line);
    std::string cell;
    double v[12];
    int n = 0;
    while (std::getline(row, cell, ',')) {
      if (n == 12) break;
      std::size_t used = 0;
      try {
        v[n] = std::stod(cell, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != cell.size()) {
        throw Error(SourceLoc{name, line_no, 1}, fmt::format("bad number '{}'", cell));
      }
      ++n;
    }
    if (n != 12 || !row.eof()) {
      throw Error(SourceLoc{name, line_no, 1}, "expected 12 comma-separated values");
    }
    ReferencePoint p;
    p.triangle = int32_t(v[0]);
    p.u = float(v[1]);
    p.v = float(v[2]);
    p.position = Vec3(float(v[3]), float(v[4]), float(v[5]));
    ReferenceValue r;
    r.radiosity = DVec3(v[6], v[7], v[8]);
    r.standard_error = DVec3(v[9], v[10], v[11]);
    set.points.push_back(p);
    set.values.push_back(r);
  }
  if (!header) throw Error(SourceLoc{name, line_no, 0}, "no header line");
  return set;
}

ReferenceSet read_reference_csv_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(SourceLoc{path, 0, 0}, "cannot read the reference file");
  return read_reference_csv(in, path);
}

}  // namespace rad
