// Progress reporting: a bar on a terminal, plain lines otherwise, nothing when quiet.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace rad {

/// Reports the progress of a long task on stderr. Not thread-safe: call from the driving thread.
class Progress {
 public:
  enum class Mode { Auto, Bar, Lines, Quiet };
  explicit Progress(Mode mode = Mode::Auto);
  ~Progress();

  /// Sets the fraction done (0..1) and a short status text; redraws at most ~10 times a second
  /// on a terminal, and prints a plain line at most every few seconds otherwise.
  void update(double fraction, const std::string& status);
  /// Ends the bar (a newline on a terminal) and prints a final status.
  void finish(const std::string& status);

  bool quiet() const { return mode_ == Mode::Quiet; }

 private:
  Mode mode_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace rad
