// The program's operator new, replaced (a replaceable allocation function, [new.delete]) so that
// big blocks ask for transparent huge pages where the kernel leaves them to madvise (Debian's
// default): a block of a million triangles is then faulted in 2 MiB at a time, not 4 KiB, which
// saves most of the page faults that would take a quarter of a model's import. Everything else is
// malloc. (No new_handler is called on failure: rad sets none.)
// Linked into the rad executable only; not under the sanitizers, which bring their own.
#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <new>

namespace {

constexpr std::size_t kHugePage = std::size_t(2) << 20;
// At 32 MiB and more glibc always maps a block of its own (its mmap threshold never rises
// above that), so the advice never lands on heap memory that small blocks will reuse.
constexpr std::size_t kBigBlock = std::size_t(32) << 20;

void* allocate(std::size_t n) {
  void* p = std::malloc(n > 0 ? n : 1);
  if (p == nullptr) throw std::bad_alloc();
  if (n >= kBigBlock) {
    // The whole huge pages inside the block (its ends are shared with malloc's bookkeeping).
    const std::uintptr_t lo = (std::uintptr_t(p) + kHugePage - 1) & ~(kHugePage - 1);
    const std::uintptr_t hi = (std::uintptr_t(p) + n) & ~(kHugePage - 1);
    if (hi > lo) madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);  // a hint only
  }
  return p;
}

}  // namespace

void* operator new(std::size_t n) { return allocate(n); }
void* operator new[](std::size_t n) { return allocate(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

#endif
