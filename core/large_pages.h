#pragma once
// Memory for arrays of hundreds of MB (the decimator's per-vertex, per-face
// and per-edge arrays of a multi-million-triangle scan), backed by
// transparent huge pages where the kernel allows them.
//
// Why: the cost of such an array is mostly its first touch, one page fault
// per 4 KiB page. On this project's machines (virtual machines whose host
// backs guest memory on demand) a 4 KiB fault costs about 15 us, so 1.4 GB
// of fresh arrays cost 5 s of faults, more than the decimation itself
// (measured: 512 MB touched by one thread 1.7 s with 4 KiB pages, 0.88 s
// with 2 MiB pages, 0.29 s with 2 MiB pages on two threads, 0.03 s with
// 2 MiB pages the process freed a moment before). On a bare-metal Linux
// the faults are ten times cheaper and huge pages still save TLB misses.
// Arrays below 4 MiB come from the normal allocator (see large_pages.cpp).
//
// Linux only (madvise); elsewhere these are plain allocations.
#include <cstddef>
#include <new>
#include <vector>

namespace hs {

// At least `bytes`, aligned to 64 bytes; huge-page backed (2 MiB aligned,
// MADV_HUGEPAGE, whole huge pages) from 4 MiB up. Contents uninitialised. Throws
// std::bad_alloc.
void* allocateLarge(size_t bytes);
// Frees what allocateLarge(bytes) returned (the same `bytes`).
void freeLarge(void* p, size_t bytes) noexcept;

// Asks the kernel for huge pages on the 2 MiB-aligned part of [p, p+bytes)
// of memory that is not yet touched (e.g. a std::vector's reserved
// capacity), and faults it in on `threads` threads (MADV_POPULATE_WRITE,
// contents unchanged), so that the single-threaded value-initialisation
// that follows writes to pages already there.
void adviseAndPopulate(void* p, size_t bytes, unsigned threads);

// std::allocator that takes large blocks from allocateLarge.
template <class T>
struct LargeAllocator {
  using value_type = T;
  LargeAllocator() = default;
  template <class U>
  LargeAllocator(const LargeAllocator<U>&) {}
  T* allocate(size_t n) {
    if (n > size_t(-1) / sizeof(T)) throw std::bad_alloc();
    return static_cast<T*>(allocateLarge(n * sizeof(T)));
  }
  void deallocate(T* p, size_t n) noexcept { freeLarge(p, n * sizeof(T)); }
  template <class U>
  bool operator==(const LargeAllocator<U>&) const {
    return true;
  }
};

// Resizes `v` (of trivially copyable elements) to n; storage it has to
// allocate for that is asked for huge pages and faulted in on `threads`
// workers before resize() writes it on one thread (for vectors whose type
// is not ours to change, like a MeshData's).
template <class Vector>
void resizeOnHugePages(Vector& v, size_t n, unsigned threads) {
  if (n > v.capacity()) {
    v.reserve(n);
    adviseAndPopulate(v.data() + v.size(), (n - v.size()) * sizeof(*v.data()), threads);
  }
  v.resize(n);
}

// A std::vector on such memory (value-initialised as usual on resize:
// prefer UninitArray-style buffers where a parallel pass writes every
// element anyway).
template <class T>
using LargeVector = std::vector<T, LargeAllocator<T>>;

}  // namespace hs
