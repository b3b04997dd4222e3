#include "core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "core/error.h"

namespace rad {

namespace {
// "<path>.tmp-<pid>": the writer's pid tells a live writer from one that died.
constexpr const char* kTemporaryTag = ".tmp-";

void sync_path(const std::string& p, const std::string& name) {
  const int fd = ::open(p.c_str(), O_RDONLY | O_CLOEXEC);
  const bool ok = fd >= 0 && ::fsync(fd) == 0;
  if (fd >= 0) ::close(fd);
  if (!ok)
    throw Error(SourceLoc{name}, std::string("cannot sync to disk: ") + std::strerror(errno));
}
}  // namespace

void remove_stale_temporaries(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string prefix = target.filename().string() + kTemporaryTag;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(folder, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::strtol(digits.c_str(), nullptr, 10);
    // Another run still writing it keeps it; a run that died (kill -9) left it.
    if (pid > 0 && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH) fs::remove(e.path(), ec);
  }
}

AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)), temp_(path_ + kTemporaryTag + std::to_string(getpid())) {
  out_.open(temp_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    throw Error(SourceLoc{path_}, std::string("cannot write: ") + std::strerror(errno));
  }
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::remove(temp_.c_str());
  }
}

void AtomicFile::commit() {
  out_.flush();
  const bool ok = bool(out_);
  out_.close();
  if (!ok || out_.fail()) throw Error(SourceLoc{path_}, "write failed (disk full?)");
  if (durable_) {
    // The data must be on disk before the rename makes it the file (a crash in between would
    // otherwise leave a complete name over incomplete data), and the rename itself after it.
    sync_path(temp_, path_);
  }
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
    throw Error(SourceLoc{path_}, std::string("cannot rename into place: ") + std::strerror(errno));
  }
  committed_ = true;
  if (durable_) {
    const size_t slash = path_.find_last_of('/');
    sync_path(slash == std::string::npos ? "." : path_.substr(0, slash + 1), path_);
  }
}

}  // namespace rad
