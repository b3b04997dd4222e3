#include "app/batch_summary.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"

namespace rad {

namespace {

// flock(2) on a file of its own (not batch.json, which is replaced by rename): held until the
// descriptor closes, also when the process dies.
class FolderLock {
 public:
  explicit FolderLock(const std::string& path) : fd_(::open(path.c_str(), O_RDWR | O_CREAT, 0644)) {
    if (fd_ < 0) throw Error(SourceLoc{path}, std::string("cannot open: ") + std::strerror(errno));
    while (::flock(fd_, LOCK_EX) != 0) {
      if (errno != EINTR) {
        ::close(fd_);
        throw Error(SourceLoc{path}, std::string("cannot lock: ") + std::strerror(errno));
      }
    }
  }
  ~FolderLock() { ::close(fd_); }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_;
};

}  // namespace

void merge_batch_record(const std::string& dir, const BatchRecord& r) {
  namespace fs = std::filesystem;
  using nlohmann::json;
  const FolderLock lock((fs::path(dir) / "batch.lock").string());
  const std::string path = (fs::path(dir) / "batch.json").string();
  json j;
  if (std::ifstream in(path); in) {
    j = json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (!j.is_object() || !j.contains("scenes") || !j["scenes"].is_object()) {
      warn(SourceLoc{path}, "not a rad batch summary: replaced");
      j = json();
    }
  }
  j["schema"] = "rad-batch";
  j["version"] = 1;
  if (!j.contains("scenes")) j["scenes"] = json::object();
  j["scenes"][r.name] = {{"scene", r.scene},     {"status", r.status}, {"detail", r.detail},
                         {"seconds", r.seconds}, {"shots", r.shots},   {"vertices", r.vertices},
                         {"shard", r.shard},     {"shards", r.shards}};
  AtomicFile f(path);
  f.stream() << j.dump(2) << "\n";
  f.commit();
}

}  // namespace rad
