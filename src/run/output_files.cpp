#include "run/output_files.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/error.h"

namespace rad {

namespace fs = std::filesystem;

void check_writable(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    throw Error(SourceLoc{path}, "is a folder: give a file name for this output");
  }
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::exists(folder, ec)) {
    throw Error(SourceLoc{path}, "cannot write: the folder '" + folder.string() +
                                     "' does not exist; create it or give another path");
  }
  if (!fs::is_directory(folder, ec)) {
    throw Error(SourceLoc{path}, "cannot write: '" + folder.string() + "' is not a folder");
  }
  // Only making a file there tells (permissions, a read-only file system, quotas); the
  // outputs' own temporaries take the same kind of name.
  const std::string probe = path + ".tmp-" + std::to_string(getpid()) + "-probe";
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw Error(SourceLoc{path}, std::string("cannot write: ") + std::strerror(errno) +
                                     "; give a path in a folder you can write to");
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

StagedFiles::~StagedFiles() {
  for (const auto& [temporary, final] : files_) std::remove(temporary.c_str());
}

void StagedFiles::write(const std::string& path,
                        const std::function<void(const std::string&)>& write) {
  const std::string temporary = path + ".tmp-" + std::to_string(getpid()) + "-" +
                                std::to_string(files_.size()) + fs::path(path).extension().string();
  files_.emplace_back(temporary, path);
  try {
    write(temporary);
  } catch (const Error& e) {
    if (e.loc().file != temporary) throw;
    SourceLoc loc = e.loc();
    loc.file = path;
    throw Error(loc, e.message());
  }
}

void StagedFiles::commit() {
  while (!files_.empty()) {
    const auto [temporary, final] = files_.front();
    if (std::rename(temporary.c_str(), final.c_str()) != 0) {
      throw Error(SourceLoc{final},
                  std::string("cannot rename into place: ") + std::strerror(errno));
    }
    files_.erase(files_.begin());
  }
}

}  // namespace rad
