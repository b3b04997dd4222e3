// Flush-to-zero and denormals-are-zero for a scope (the x86 SSE control register, per thread).
#pragma once

#include <pmmintrin.h>
#include <xmmintrin.h>

namespace rad {

/// Embree wants both modes on every thread that traces. Writing the control register stalls the
/// pipeline, so this writes it only when a mode is off and restores only what it changed: the
/// solver sets the modes once per task range, and the per-batch scope inside the Embree backend
/// then costs one register read.
class ScopedFlushDenormals {
 public:
  ScopedFlushDenormals() : saved_(_mm_getcsr()) {
    const unsigned wanted = saved_ | _MM_FLUSH_ZERO_ON | _MM_DENORMALS_ZERO_ON;
    changed_ = wanted != saved_;
    if (changed_) _mm_setcsr(wanted);
  }
  ~ScopedFlushDenormals() {
    if (changed_) _mm_setcsr(saved_);
  }
  ScopedFlushDenormals(const ScopedFlushDenormals&) = delete;
  ScopedFlushDenormals& operator=(const ScopedFlushDenormals&) = delete;

 private:
  unsigned saved_;
  bool changed_;
};

}  // namespace rad
