// Coverage-preserving mip chains for alpha cut-out textures
// (mesh/alpha_coverage_mips.h) against the property they promise, counted
// directly on every level where a bilinear sampler reads it: the share of
// samples at or over the threshold stays level 0's, where the plain box
// filter (GL's glGenerateMipmap) loses most of a needle texture's cover; the leaves' colour is not darkened by the transparent texels
// around them; sizes follow GL's chain, odd and non-square ones too; an
// opaque texture and degenerate input are left alone.
#include <QtTest>

#include <cmath>

#include "core/srgb.h"
#include "leaf_texture.h"
#include "foliage/plants.h"
#include "mesh/alpha_coverage_mips.h"

using namespace hs;

namespace {

mesh::Texture leaves(int w, int h, double radius, int count, uint32_t seed) {
  return test::leafTexture(w, h, radius, count, seed);
}

// The mean linear green of the texels that pass the threshold.
double passingGreen(const std::vector<uint8_t>& rgba, float threshold) {
  double g = 0.0;
  size_t n = 0;
  for (size_t i = 0; i + 3 < rgba.size(); i += 4)
    if (rgba[i + 3] >= threshold * 255.0f) g += srgb8ToLinear(rgba[i + 1]), ++n;
  return n ? g / double(n) : 0.0;
}

}  // namespace

class TestAlphaMips : public QObject {
  Q_OBJECT
 private slots:
  void coverageStaysLevelZeros_data() {
    QTest::addColumn<int>("which");
    QTest::newRow("discs") << 0;
    QTest::newRow("conifer needles") << 1;
    QTest::newRow("broadleaf") << 2;
  }
  void coverageStaysLevelZeros() {
    QFETCH(int, which);
    // Random leaves, and the generated plants' own leaf textures
    // (foliage/plants.h): thin needles are what the box filter loses most.
    const mesh::Texture t = which == 0   ? leaves(256, 256, 5.0, 500, 7)
                            : which == 1 ? foliage::leafTexture(foliage::PlantKind::Conifer, 256)
                                         : foliage::leafTexture(foliage::PlantKind::Broadleaf, 256);
    for (float threshold : {0.5f, 0.3f, 0.8f}) {
      const double c0 = mesh::alphaCoverage(t.rgba, threshold);
      QVERIFY2(c0 > 0.15 && c0 < 0.7, qPrintable(QString::number(c0)));
      const std::vector<mesh::MipLevel> kept = mesh::coveragePreservingMips(t, threshold);
      const std::vector<mesh::MipLevel> box = mesh::boxFilteredMips(t);
      QCOMPARE(kept.size(), size_t(8));  // 128 .. 1
      QCOMPARE(box.size(), kept.size());
      for (size_t i = 0; i < kept.size(); ++i) {
        const size_t samples = size_t(kept[i].width) * size_t(kept[i].height) * 4;
        // Where a bilinear sampler reads each level (what the renderer's
        // cut sees), against level 0's texels.
        const double c = mesh::filteredAlphaCoverage(kept[i], threshold);
        const double b = mesh::filteredAlphaCoverage(box[i], threshold);
        if (threshold == 0.5f) qInfo("level %zu (%d px): coverage %.3f kept, %.3f box-filtered, level 0 %.3f", i + 1,
                                     kept[i].width, c, b, c0);
        // Within 2 % where the level has a thousand samples or more
        // (samples of one value pass or fail together: fewer, coarser).
        if (samples >= 1024)
          QVERIFY2(std::abs(c - c0) <= 0.02,
                   qPrintable(QString("threshold %1 level %2: %3 for %4").arg(threshold).arg(i + 1).arg(c).arg(c0)));
        // Needles four levels down: the box filter loses most of them.
        if (which == 1 && threshold == 0.5f && i == 3) QVERIFY2(b < 0.5 * c0, qPrintable(QString::number(b)));
      }
      // The leaves stay their colour a few levels down (weighted by alpha:
      // the transparent black does not darken them).
      const double g0 = passingGreen(t.rgba, threshold), g3 = passingGreen(kept[2].rgba, threshold);
      QVERIFY2(std::abs(g3 - g0) < 0.05 * g0, qPrintable(QString("%1 against %2").arg(g3).arg(g0)));
    }
  }

  void sizesFollowGlsChain() {
    const mesh::Texture t = leaves(37, 12, 2.0, 20, 3);
    const std::vector<mesh::MipLevel> m = mesh::coveragePreservingMips(t, 0.5f);
    const std::vector<std::pair<int, int>> want = {{18, 6}, {9, 3}, {4, 1}, {2, 1}, {1, 1}};
    QCOMPARE(m.size(), want.size());
    for (size_t i = 0; i < m.size(); ++i) {
      QCOMPARE(std::make_pair(m[i].width, m[i].height), want[i]);
      QCOMPARE(m[i].rgba.size(), size_t(m[i].width) * size_t(m[i].height) * 4);
    }
    // The odd last column and row are not skipped: a texel only there
    // still shows in the level below.
    mesh::Texture edge;
    edge.width = edge.height = 3;
    edge.rgba.assign(36, 0);
    edge.rgba[(2 * 3 + 2) * 4 + 3] = 255;  // the corner texel (2, 2) alone
    const std::vector<mesh::MipLevel> e = mesh::boxFilteredMips(edge);
    QCOMPARE(e.size(), size_t(1));
    QVERIFY(e[0].rgba[3] > 0);
  }

  void opaqueAndDegenerateInput() {
    mesh::Texture opaque;
    opaque.width = opaque.height = 8;
    opaque.rgba.assign(8 * 8 * 4, 255);
    for (const mesh::MipLevel& l : mesh::coveragePreservingMips(opaque, 0.5f))
      for (size_t i = 3; i < l.rgba.size(); i += 4) QCOMPARE(int(l.rgba[i]), 255);
    mesh::Texture empty;
    QVERIFY(mesh::coveragePreservingMips(empty, 0.5f).empty());
    mesh::Texture damaged;
    damaged.width = damaged.height = 4;
    damaged.rgba.assign(10, 0);  // fewer bytes than its size
    QVERIFY(mesh::coveragePreservingMips(damaged, 0.5f).empty());
    mesh::Texture one;
    one.width = one.height = 1;
    one.rgba = {1, 2, 3, 4};
    QVERIFY(mesh::coveragePreservingMips(one, 0.5f).empty());  // no level below 1x1
    // A threshold outside (0, 1): the weighted box filter, unscaled.
    const mesh::Texture t = leaves(64, 64, 3.0, 40, 5);
    const auto a = mesh::coveragePreservingMips(t, 0.0f), b = mesh::coveragePreservingMips(t, 1.5f);
    QCOMPARE(a.size(), size_t(6));
    for (size_t i = 0; i < a.size(); ++i) QVERIFY(a[i].rgba == b[i].rgba);
  }
};

QTEST_APPLESS_MAIN(TestAlphaMips)
#include "test_alpha_mips.moc"
