#include "mesh/weld.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <memory>

#include "core/large_pages.h"
#include "core/parallel.h"
#include "mesh/radix_sort.h"

namespace hs::mesh {
namespace {

// Bits of a float with -0.0 folded onto +0.0 (the same point).
inline uint32_t canonicalBits(float f) {
  uint32_t b = std::bit_cast<uint32_t>(f);
  return b == 0x80000000u ? 0u : b;
}

inline uint64_t mix(uint64_t h, uint32_t v) {
  h ^= v;
  h *= 0x9E3779B97F4A7C15ull;
  return h ^ (h >> 29);
}

}  // namespace

std::vector<uint32_t> weldMap(std::span<const glm::vec3> positions, std::span<const glm::vec2> uvs,
                              std::span<const glm::vec3> normals, uint32_t& uniqueCount, unsigned threads) {
  const size_t n = positions.size();
  const bool useUv = uvs.size() == n && n > 0;
  const bool useNormal = normals.size() == n && n > 0;
  constexpr size_t kWords = 8;  // 3 position + 2 uv + 3 normal
  auto keyOf = [&](size_t i, uint32_t (&k)[kWords]) {
    const glm::vec3& p = positions[i];
    k[0] = canonicalBits(p.x), k[1] = canonicalBits(p.y), k[2] = canonicalBits(p.z);
    k[3] = useUv ? canonicalBits(uvs[i].x) : 0u;
    k[4] = useUv ? canonicalBits(uvs[i].y) : 0u;
    k[5] = useNormal ? canonicalBits(normals[i].x) : 0u;
    k[6] = useNormal ? canonicalBits(normals[i].y) : 0u;
    k[7] = useNormal ? canonicalBits(normals[i].z) : 0u;
  };
  auto hashOf = [](const uint32_t (&k)[kWords]) {
    uint64_t h = 0;
    for (uint32_t w : k) h = mix(h, w);
    return h;
  };
  auto same = [&](size_t a, const uint32_t (&k)[kWords]) {
    uint32_t o[kWords];
    keyOf(a, o);
    return std::memcmp(k, o, sizeof o) == 0;
  };
  // Open addressing, power-of-two table at most half full, filled by all
  // workers at once without locks: an empty slot is claimed by
  // compare-and-swap, and a slot of the same key keeps the smallest vertex
  // index (an atomic minimum). Which slot a key lands in depends on timing;
  // what the slot holds in the end (the key's first vertex) does not, so
  // the ids below are the same for any number of threads. A std::unordered_map
  // spends most of its time in malloc at millions of vertices.
  size_t cap = 16;
  while (cap < n * 2) cap <<= 1;
  const auto table = std::make_unique_for_overwrite<std::atomic<uint32_t>[]>(cap);
  const unsigned workers = resolveThreads(threads);
  parallelRanges(cap, workers, [&](size_t b, size_t e, unsigned) {
    for (size_t i = b; i < e; ++i) table[i].store(UINT32_MAX, std::memory_order_relaxed);
  });
  parallelRanges(n, workers, [&](size_t b, size_t e, unsigned) {
    uint32_t k[kWords];
    for (size_t i = b; i < e; ++i) {
      keyOf(i, k);
      for (size_t slot = size_t(hashOf(k)) & (cap - 1);; slot = (slot + 1) & (cap - 1)) {
        uint32_t cur = table[slot].load(std::memory_order_relaxed);
        if (cur == UINT32_MAX) {
          if (table[slot].compare_exchange_strong(cur, uint32_t(i), std::memory_order_relaxed)) break;
          // Lost the race: `cur` now holds the winner; look at it below.
        }
        if (same(cur, k)) {
          while (uint32_t(i) < cur && !table[slot].compare_exchange_weak(cur, uint32_t(i), std::memory_order_relaxed)) {
          }
          break;
        }
      }
    }
  });
  // Every vertex finds its key's first vertex; those that are first get
  // ids in index order (a prefix count per range), the rest take theirs.
  std::vector<uint32_t> remap(n);
  std::vector<size_t> firsts(workers + 1, 0);
  parallelRanges(n, workers, [&](size_t b, size_t e, unsigned w) {
    uint32_t k[kWords];
    size_t count = 0;
    for (size_t i = b; i < e; ++i) {
      keyOf(i, k);
      size_t slot = size_t(hashOf(k)) & (cap - 1);
      while (!same(table[slot].load(std::memory_order_relaxed), k)) slot = (slot + 1) & (cap - 1);
      remap[i] = table[slot].load(std::memory_order_relaxed);
      count += remap[i] == i;
    }
    firsts[w + 1] = count;
  }, 1);
  for (unsigned w = 0; w < workers; ++w) firsts[w + 1] += firsts[w];
  parallelRanges(n, workers, [&](size_t b, size_t e, unsigned w) {
    uint32_t next = uint32_t(firsts[w]);
    for (size_t i = b; i < e; ++i)
      if (remap[i] == i) remap[i] = next++ | 0x80000000u;  // mark: an id, not an index
  }, 1);
  parallelRanges(n, workers, [&](size_t b, size_t e, unsigned) {
    for (size_t i = b; i < e; ++i)
      if (!(remap[i] & 0x80000000u)) remap[i] = remap[remap[i]] & 0x7fffffffu;
  });
  parallelRanges(n, workers, [&](size_t b, size_t e, unsigned) {
    for (size_t i = b; i < e; ++i) remap[i] &= 0x7fffffffu;
  });
  uniqueCount = uint32_t(firsts[workers]);
  return remap;
}

PositionWedgeWeld weldPositionsAndWedges(std::span<const glm::vec3> positions, std::span<const glm::vec2> uvs,
                                         unsigned threads) {
  PositionWedgeWeld weld;
  const size_t n = positions.size();
  const bool useUv = uvs.size() == n && n > 0;
  const unsigned workers = resolveThreads(threads);
  glm::vec3 lo(HUGE_VALF), hi(-HUGE_VALF);
  for (const auto& p : positions)
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) lo = glm::min(lo, p), hi = glm::max(hi, p);
  if (!(lo.x <= hi.x)) lo = hi = glm::vec3(0.0f);
  const glm::vec3 scale = 1023.0f / glm::max(hi - lo, glm::vec3(1e-30f));
  // Every array of n here is first touched on huge pages by all workers
  // (resizeOnHugePages): zero-filled by std::vector on one thread, the
  // tile's 2.5M vertices cost 20k page faults, most of this weld's time.
  std::vector<uint64_t> order;
  resizeOnHugePages(order, n, workers);
  parallelRanges(n, workers, [&](size_t b, size_t e, unsigned) {
    for (size_t i = b; i < e; ++i) {
      // Non-finite coordinates clamp into some cell; equal bits still meet.
      const glm::vec3 c = glm::clamp((positions[i] - lo) * scale, glm::vec3(0.0f), glm::vec3(1023.0f));
      const glm::uvec3 q = glm::all(glm::equal(c, c)) ? glm::uvec3(c) : glm::uvec3(0);
      order[i] = (uint64_t(mortonCode10(q.x, q.y, q.z)) << 32) | i;
    }
  });
  radixSortByKey(order, 30, workers);
  // First vertex (smallest index) of each position and each position+UV.
  std::vector<uint32_t> posRep, wedgeRep;
  resizeOnHugePages(posRep, n, workers);
  resizeOnHugePages(wedgeRep, n, workers);
  auto posKey = [&](uint32_t i) {
    const glm::vec3& p = positions[i];
    return std::array<uint32_t, 3>{canonicalBits(p.x), canonicalBits(p.y), canonicalBits(p.z)};
  };
  auto uvKey = [&](uint32_t i) {
    return useUv ? std::array<uint32_t, 2>{canonicalBits(uvs[i].x), canonicalBits(uvs[i].y)} : std::array<uint32_t, 2>{0, 0};
  };
  // Runs of equal code are independent: cut the sorted list at run starts.
  std::vector<size_t> cut{0};
  for (unsigned w = 1; w < workers; ++w) {
    size_t at = n * w / workers;
    while (at > 0 && at < n && (order[at] >> 32) == (order[at - 1] >> 32)) ++at;
    cut.push_back(std::max(cut.back(), at));
  }
  cut.push_back(n);
  parallelTasks(workers, workers, [&](size_t w, unsigned) {
    std::vector<uint32_t> run;
    for (size_t r = cut[w]; r < cut[w + 1];) {
      size_t e = r + 1;
      while (e < cut[w + 1] && (order[e] >> 32) == (order[r] >> 32)) ++e;
      run.clear();
      for (size_t k = r; k < e; ++k) run.push_back(uint32_t(order[k]));
      // Order the run by (position, UV, index): equal keys become
      // neighbours and each group's first is its smallest index.
      std::sort(run.begin(), run.end(), [&](uint32_t a, uint32_t b) {
        const auto pa = posKey(a), pb = posKey(b);
        if (pa != pb) return pa < pb;
        const auto ua = uvKey(a), ub = uvKey(b);
        if (ua != ub) return ua < ub;
        return a < b;
      });
      for (size_t k = 0; k < run.size();) {
        size_t g = k + 1;
        const auto pk = posKey(run[k]);
        while (g < run.size() && posKey(run[g]) == pk) ++g;
        // [k, g): one position; its smallest index is the least of the
        // first of each UV subgroup.
        uint32_t posFirst = UINT32_MAX;
        for (size_t u = k; u < g;) {
          size_t v = u + 1;
          const auto uk = uvKey(run[u]);
          while (v < g && uvKey(run[v]) == uk) ++v;
          for (size_t x = u; x < v; ++x) wedgeRep[run[x]] = run[u];
          posFirst = std::min(posFirst, run[u]);
          u = v;
        }
        for (size_t x = k; x < g; ++x) posRep[run[x]] = posFirst;
        k = g;
      }
      r = e;
    }
  });
  order = {};
  // Ids in order of first occurrence: a prefix count of the firsts, which
  // are also each id's first vertex.
  auto number = [&](std::vector<uint32_t>& rep, std::vector<uint32_t>& out, std::vector<uint32_t>& firstOf,
                    uint32_t& count) {
    std::vector<size_t> firsts(workers + 1, 0);
    resizeOnHugePages(out, n, workers);
    parallelRanges(n, workers, [&](size_t b, size_t e, unsigned w) {
      size_t c = 0;
      for (size_t i = b; i < e; ++i) c += rep[i] == i;
      firsts[w + 1] = c;
    }, 1);
    for (unsigned w = 0; w < workers; ++w) firsts[w + 1] += firsts[w];
    count = uint32_t(firsts[workers]);
    resizeOnHugePages(firstOf, count, workers);
    parallelRanges(n, workers, [&](size_t b, size_t e, unsigned w) {
      uint32_t next = uint32_t(firsts[w]);
      for (size_t i = b; i < e; ++i)
        if (rep[i] == i) firstOf[next] = uint32_t(i), out[i] = next++;
    }, 1);
    parallelRanges(n, workers, [&](size_t b, size_t e, unsigned) {
      for (size_t i = b; i < e; ++i)
        if (rep[i] != i) out[i] = out[rep[i]];  // the first comes earlier: already numbered
    });
  };
  number(posRep, weld.posOf, weld.posFirst, weld.positionCount);
  if (useUv) {
    number(wedgeRep, weld.wedgeOf, weld.wedgeFirst, weld.wedgeCount);
  } else {
    weld.wedgeOf = weld.posOf, weld.wedgeFirst = weld.posFirst;
    weld.wedgeCount = weld.positionCount;
  }
  return weld;
}

size_t weldExactDuplicates(MeshData& mesh) {
  uint32_t unique = 0;
  const std::vector<uint32_t> remap = weldMap(mesh.positions, mesh.uvs, mesh.normals, unique);
  const size_t n = mesh.positions.size();
  if (unique == n) return 0;
  for (uint32_t& idx : mesh.indices)
    if (idx < n) idx = remap[idx];  // out-of-range indices are the cleaner's to report
  auto compact = [&](auto& arr) {
    if (arr.size() != n) return;
    std::remove_reference_t<decltype(arr)> out(unique);
    // Ids follow first occurrence, so writing in order keeps the first copy.
    for (size_t i = n; i-- > 0;) out[remap[i]] = arr[i];
    arr = std::move(out);
  };
  compact(mesh.positions);
  compact(mesh.uvs);
  compact(mesh.normals);
  return n - unique;
}

}  // namespace hs::mesh
