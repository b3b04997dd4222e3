#include "export/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/error.h"

namespace rad {

AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)), temp_(path_ + ".tmp-" + std::to_string(getpid())) {
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
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
    throw Error(SourceLoc{path_}, std::string("cannot rename into place: ") + std::strerror(errno));
  }
  committed_ = true;
}

}  // namespace rad
