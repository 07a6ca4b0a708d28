#include "core/large_pages.h"

#include <cstdint>
#include <cstdlib>

#include "core/parallel.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace hs {
namespace {

[[maybe_unused]] constexpr size_t kHuge = size_t(2) << 20;  // x86-64 and arm64 (4 KiB base pages) huge page size
// Blocks from 4 MiB get a mapping of their own on huge pages. Smaller ones
// come from malloc, which keeps freed memory in its heap and hands it out
// again already faulted in: a process that decimates small meshes again
// and again (previews, LOD levels) pays their faults once (the bunny's
// arrays are all below this).
[[maybe_unused]] constexpr size_t kHugeFrom = size_t(4) << 20;

#if defined(__linux__) && defined(MADV_HUGEPAGE)
// Mapped size for `bytes`: whole huge pages.
size_t mappedSize(size_t bytes) { return (bytes + kHuge - 1) & ~(kHuge - 1); }
#endif

}  // namespace

void* allocateLarge(size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (bytes >= kHugeFrom) {
    const size_t size = mappedSize(bytes);
    if (size < bytes) throw std::bad_alloc();
    // Over-map by one huge page and trim, so the block starts on a huge
    // page boundary and every page of it can be a huge one.
    void* raw = mmap(nullptr, size + kHuge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) throw std::bad_alloc();
    const uintptr_t base = reinterpret_cast<uintptr_t>(raw);
    const uintptr_t aligned = (base + kHuge - 1) & ~uintptr_t(kHuge - 1);
    if (aligned > base) munmap(raw, aligned - base);
    const uintptr_t end = aligned + size, rawEnd = base + size + kHuge;
    if (rawEnd > end) munmap(reinterpret_cast<void*>(end), rawEnd - end);
    void* p = reinterpret_cast<void*>(aligned);
    madvise(p, size, MADV_HUGEPAGE);  // a hint: where THP is off it fails and 4 KiB pages serve
    return p;
  }
#endif
  void* p = std::aligned_alloc(64, (bytes + 63) & ~size_t(63));
  if (!p && bytes) throw std::bad_alloc();
  return p;
}

void freeLarge(void* p, size_t bytes) noexcept {
  if (!p) return;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (bytes >= kHugeFrom) {
    munmap(p, mappedSize(bytes));
    return;
  }
#endif
  std::free(p);
}

void adviseAndPopulate(void* p, size_t bytes, unsigned threads) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(p) + kHuge - 1) & ~uintptr_t(kHuge - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(p) + bytes) & ~uintptr_t(kHuge - 1);
  if (end <= begin) return;
  const size_t pages = (end - begin) / kHuge;
  madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#if defined(MADV_POPULATE_WRITE)
  // Faults the pages in (as a write would, contents unchanged) on every
  // worker: on these machines the faults, not the writes, are the cost.
  // Kernels before 5.14 refuse it; the first writes fault the pages then.
  parallelRanges(pages, threads, [&](size_t b, size_t e, unsigned) {
    madvise(reinterpret_cast<void*>(begin + b * kHuge), (e - b) * kHuge, MADV_POPULATE_WRITE);
  }, 8);
#else
  (void)pages, (void)threads;
#endif
#else
  (void)p, (void)bytes, (void)threads;
#endif
}

}  // namespace hs
