// Procedural plants: the same seed grows the same mesh bit for bit, another
// seed another; every kind is a valid mesh of about the asked size, with
// bark and leaf submeshes and a cut-out leaf texture.
#include <QtTest>

#include <cstring>

#include "foliage/plants.h"

using namespace hs::foliage;

namespace {

bool identical(const hs::mesh::MeshData& a, const hs::mesh::MeshData& b) {
  return a.positions.size() == b.positions.size() && a.indices == b.indices &&
         std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(glm::vec3)) == 0 &&
         std::memcmp(a.normals.data(), b.normals.data(), a.normals.size() * sizeof(glm::vec3)) == 0;
}

}  // namespace

class TestFoliagePlants : public QObject {
  Q_OBJECT
 private slots:
  void everyKind_data() {
    QTest::addColumn<int>("kind");
    for (int k = 0; k <= int(PlantKind::Rock); ++k) QTest::newRow(plantKindName(PlantKind(k))) << k;
  }
  void everyKind() {
    QFETCH(int, kind);
    const PlantParams p = defaultPlant(PlantKind(kind), 17);
    PlantStats st;
    const hs::mesh::MeshData a = generatePlant(p, &st), b = generatePlant(p);
    QVERIFY(identical(a, b));
    PlantParams other = p;
    other.seed = 18;
    QVERIFY(!identical(a, generatePlant(other)));
    QVERIFY(a.triangleCount() > 20 && a.triangleCount() < 400000);
    QCOMPARE(a.normals.size(), a.positions.size());
    QCOMPARE(a.uvs.size(), a.positions.size());
    for (uint32_t i : a.indices) QVERIFY(i < a.positions.size());
    for (const glm::vec3& v : a.positions) QVERIFY(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
    uint32_t covered = 0;
    for (const auto& s : a.submeshes) covered += s.indexCount;
    QCOMPARE(size_t(covered), a.indices.size());
    const hs::mesh::Bounds bb = a.bounds();
    const double top = double(bb.max.z);
    qInfo("%s: %zu triangles, %zu stems, %zu leaves, %.2f m tall", plantKindName(PlantKind(kind)), a.triangleCount(),
          st.stems, st.leaves, top);
    if (PlantKind(kind) == PlantKind::Rock) {
      const double w = double(bb.max.x - bb.min.x);
      QVERIFY(w > 0.5 * p.height && w < 1.6 * p.height);
      QCOMPARE(a.submeshes.size(), size_t(1));
    } else {
      QVERIFY2(top > 0.4 * p.height && top < 1.3 * p.height, qPrintable(QString::number(top)));
      QCOMPARE(a.submeshes.back().material, 1);
      QCOMPARE(a.textures.size(), size_t(1));
      const auto& tex = a.textures[0];
      bool clear = false, opaque = false;
      for (size_t i = 3; i < tex.rgba.size(); i += 4) {
        clear = clear || tex.rgba[i] == 0;
        opaque = opaque || tex.rgba[i] == 255;
      }
      QVERIFY(clear && opaque);
      QVERIFY(st.leaves > 0);
    }
  }
  // Generated plants get their LOD chain from the decimator, errors
  // measured against the full plant, coarser levels with fewer triangles.
  void lodChains() {
    for (PlantKind k : {PlantKind::Broadleaf, PlantKind::Conifer, PlantKind::Grass, PlantKind::Rock}) {
      const hs::mesh::LodChain chain = generatePlantLods(defaultPlant(k, 5));
      QVERIFY2(chain.error.empty(), chain.error.c_str());
      QString row;
      for (const auto& l : chain.levels)
        row += QString(" %1 tris (%2 m)").arg(l.triangles).arg(l.hausdorff, 0, 'f', 3);
      qInfo("%s:%s", plantKindName(k), qPrintable(row));
      QVERIFY(chain.levels.size() >= 3);
      QVERIFY(chain.levels.back().triangles * 4 <= chain.levels[0].triangles);  // stems and leaves thin too
      for (size_t i = 1; i < chain.levels.size(); ++i) {
        QVERIFY(chain.levels[i].triangles < chain.levels[i - 1].triangles);
        QVERIFY(chain.levels[i].hausdorff >= chain.levels[i - 1].hausdorff);
        QVERIFY(std::isfinite(chain.levels[i].hausdorff));
      }
    }
  }
  void outOfRangeIsClampedWithAMessage() {
    PlantParams p = defaultPlant(PlantKind::Broadleaf);
    p.levels = 9;
    p.height = -3;
    std::vector<std::string> w;
    const auto m = generatePlant(p, nullptr, &w);
    QVERIFY(identical(generatePlantLods(defaultPlant(PlantKind::Shrub, 3)).levels[1].mesh,
                      generatePlantLods(defaultPlant(PlantKind::Shrub, 3)).levels[1].mesh));
    QVERIFY(m.triangleCount() > 0);
    QCOMPARE(w.size(), size_t(2));
    QVERIFY2(w[0].find("plant (broadleaf)") == 0, w[0].c_str());
  }
};

QTEST_GUILESS_MAIN(TestFoliagePlants)
#include "test_foliage_plants.moc"
