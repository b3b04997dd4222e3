#include "core/progress.h"

#include <unistd.h>

#include <algorithm>

namespace rad {

Progress::Progress(Mode mode) : mode_(mode) {
  if (mode_ == Mode::Auto) mode_ = isatty(STDERR_FILENO) ? Mode::Bar : Mode::Lines;
  start_ = last_ = std::chrono::steady_clock::now();
}

Progress::~Progress() {
  if (drawn_) std::fputc('\n', stderr);
}

void Progress::update(double fraction, const std::string& status) {
  if (mode_ == Mode::Quiet) return;
  auto now = std::chrono::steady_clock::now();
  double since = std::chrono::duration<double>(now - last_).count();
  fraction = std::clamp(fraction, 0.0, 1.0);
  if (mode_ == Mode::Bar) {
    if (drawn_ && since < 0.1) return;
    constexpr int kWidth = 30;
    int filled = static_cast<int>(fraction * kWidth + 0.5);
    std::string bar(filled, '#');
    bar.resize(kWidth, '-');
    std::fprintf(stderr, "\r[%s] %5.1f%% %s\x1b[K", bar.c_str(), fraction * 100.0, status.c_str());
    std::fflush(stderr);
    drawn_ = true;
  } else {
    if (since < 2.0) return;
    std::fprintf(stderr, "%5.1f%% %s\n", fraction * 100.0, status.c_str());
  }
  last_ = now;
}

void Progress::finish(const std::string& status) {
  if (mode_ == Mode::Quiet) return;
  if (mode_ == Mode::Bar) {
    std::string bar(30, '#');
    std::fprintf(stderr, "\r[%s] 100.0%% %s\x1b[K\n", bar.c_str(), status.c_str());
    drawn_ = false;
  } else {
    std::fprintf(stderr, "100.0%% %s\n", status.c_str());
  }
}

}  // namespace rad
