// core/large_pages and core/uninit_array (the decimator's large arrays),
// keptOffsets and keptIndices (core/parallel): blocks are aligned and
// usable end to end, advising and faulting in leaves contents as they
// were, a vector resized on huge pages keeps its elements and
// value-initialises the new ones, and the per-range offsets and the kept
// indices equal a serial compaction for any number of workers.
#include <QtTest>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "core/large_pages.h"
#include "core/parallel.h"
#include "core/uninit_array.h"

using namespace hs;

class TestLargePages : public QObject {
  Q_OBJECT

 private slots:
  void blocksAreAlignedAndWholeBothSidesOfTheHugeThreshold() {
    // Below 4 MiB (malloc), at it, and above it with a size that is not a
    // whole number of huge pages.
    for (size_t bytes : {size_t(1000), size_t(4) << 20, (size_t(9) << 20) + 12345}) {
      auto* p = static_cast<uint8_t*>(allocateLarge(bytes));
      QVERIFY(p != nullptr);
      QCOMPARE(reinterpret_cast<uintptr_t>(p) % 64, uintptr_t(0));
      if (bytes >= (size_t(4) << 20)) QCOMPARE(reinterpret_cast<uintptr_t>(p) % (size_t(2) << 20), uintptr_t(0));
      for (size_t i = 0; i < bytes; ++i) p[i] = uint8_t(i * 7 + 3);
      size_t wrong = 0;
      for (size_t i = 0; i < bytes; ++i) wrong += p[i] != uint8_t(i * 7 + 3);
      QCOMPARE(wrong, size_t(0));
      freeLarge(p, bytes);
    }
  }

  void adviseAndPopulateKeepContents() {
    const size_t n = (size_t(6) << 20) / sizeof(uint32_t) + 777;
    std::vector<uint32_t> v(n);
    std::iota(v.begin(), v.end(), 1u);
    for (unsigned threads : {1u, 2u}) {
      adviseAndPopulate(v.data(), n * sizeof(uint32_t), threads);
      size_t wrong = 0;
      for (size_t i = 0; i < n; ++i) wrong += v[i] != uint32_t(i + 1);
      QCOMPARE(wrong, size_t(0));
    }
  }

  void resizeOnHugePagesKeepsAndValueInitialises() {
    std::vector<double> v = {1.5, 2.5, 3.5};
    const size_t n = (size_t(5) << 20) / sizeof(double);
    resizeOnHugePages(v, n, 2);
    QCOMPARE(v.size(), n);
    QCOMPARE(v[0], 1.5);
    QCOMPARE(v[2], 3.5);
    QCOMPARE(size_t(std::count(v.begin() + 3, v.end(), 0.0)), n - 3);
    resizeOnHugePages(v, 2, 2);  // shrinking only shrinks
    QCOMPARE(v.size(), size_t(2));
    QCOMPARE(v[1], 2.5);
  }

  void largeVectorAndUninitArrayHoldTheirElements() {
    LargeVector<uint64_t> lv;
    for (uint64_t i = 0; i < 700000; ++i) lv.push_back(i * i);  // grows through the huge threshold
    QCOMPARE(lv[699999], uint64_t(699999) * 699999);
    UninitArray<uint32_t> a(3000000);
    for (size_t i = 0; i < a.size(); ++i) a[i] = uint32_t(i ^ 0x5a5a5a5au);
    UninitArray<uint32_t> b = std::move(a);
    QVERIFY(a.empty());
    QCOMPARE(b.size(), size_t(3000000));
    QCOMPARE(b[2999999], uint32_t(2999999u ^ 0x5a5a5a5au));
    a = std::move(b);
    QCOMPARE(a[12345], uint32_t(12345u ^ 0x5a5a5a5au));
  }

  // keptOffsets: each range's start in the compacted order, checked by
  // compacting with it and comparing with a serial compaction.
  void keptOffsetsGiveTheSerialOrder() {
    for (size_t n : {size_t(0), size_t(1), size_t(5), size_t(100000)})
      for (unsigned workers : {1u, 2u, 3u, 7u}) {
        auto keep = [](size_t i) { return (i * 2654435761u) % 5 < 2; };
        const std::vector<size_t> offsets = keptOffsets(n, workers, keep);
        QCOMPARE(offsets.size(), size_t(workers) + 1);
        std::vector<size_t> serial;
        for (size_t i = 0; i < n; ++i)
          if (keep(i)) serial.push_back(i);
        QCOMPARE(offsets[workers], serial.size());
        std::vector<size_t> compacted(serial.size(), SIZE_MAX);
        parallelRanges(n, workers, [&](size_t b, size_t e, unsigned r) {
          size_t next = offsets[r];
          for (size_t i = b; i < e; ++i)
            if (keep(i)) compacted[next++] = i;
        }, 1);
        QCOMPARE(compacted, serial);
        // keptIndices does the same compaction.
        QCOMPARE(keptIndices(n, workers, keep), std::vector<uint32_t>(serial.begin(), serial.end()));
      }
  }
};

QTEST_GUILESS_MAIN(TestLargePages)
#include "test_large_pages.moc"
