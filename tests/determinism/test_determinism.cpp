// Bit-identical results across infrastructure changes and thread counts.
//
// The hashes below were recorded from the code before the core-layer change
// (commit 1bfd080: hand-written thread pools). A solver whose output changes
// by one bit on these fixtures fails here, with the new hash printed, so a
// change to the scheduler (or anything under the solvers) that alters
// results cannot pass silently. A deliberate change of a solver updates the
// hash in the same commit and says why.
#include <QtTest>

#include <cmath>
#include <cstdint>
#include <random>

#include "mesh/mesh_import.h"
#include "meshproc/decimate.h"
#include "terrain/erosion_hydraulic.h"
#include "terrain/erosion_thermal.h"
#include "terrain/paint_rules.h"

using namespace hs;

namespace {

// FNV-1a 64 over raw bytes: local to this test so that it does not depend
// on the hashing code it helps to check.
struct Fnv {
  uint64_t h = 1469598103934665603ull;
  void bytes(const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  }
  template <class T>
  void vec(const std::vector<T>& v) {
    bytes(v.data(), v.size() * sizeof(T));
  }
};

std::vector<float> hills(int w, int h) {
  std::vector<float> v(size_t(w) * size_t(h));
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      v[size_t(y) * size_t(w) + size_t(x)] =
          100.0f + 20.0f * std::sin(float(x) * 0.15f) * std::cos(float(y) * 0.11f) + float(x) * 0.2f + u(rng);
  return v;
}

terrain::Terrain hillTerrain(int n) {
  terrain::HeightfieldDesc d;
  d.samplesX = d.samplesY = n;
  d.sizeMetres = {double(n - 1), double(n - 1)};
  d.origin = {0.0, 0.0, 200.0};
  auto r = terrain::Terrain::create(d);
  if (!r) qFatal("%s", r.error().c_str());
  terrain::Terrain t = r.take();
  const std::vector<float> h = hills(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) t.height.heights().set(x, y, h[size_t(y) * size_t(n) + size_t(x)]);
  t.height.updateAllBounds();
  return t;
}

uint64_t heightHash(const terrain::Terrain& t) {
  Fnv f;
  const int n = t.height.samplesX();
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float v = t.height.heights().get(x, y);
      f.bytes(&v, sizeof v);
    }
  return f.h;
}

mesh::MeshData bunny() {
  mesh::ImportOptions o;
  o.up = mesh::UpAxis::Z;
  mesh::ImportResult r = mesh::importMesh(HS_SOURCE_DIR "/resources/demo/stanford-bunny.obj", o);
  if (!r.ok()) qFatal("cannot read the bunny: %s", r.error.c_str());
  return std::move(*r.mesh);
}

uint64_t meshHash(const mesh::MeshData& m) {
  Fnv f;
  f.vec(m.positions);
  f.vec(m.normals);
  f.vec(m.uvs);
  f.vec(m.indices);
  return f.h;
}

void check(const char* what, uint64_t got, uint64_t recorded) {
  if (got != recorded) qWarning("%s: hash 0x%016llx, recorded 0x%016llx", what, (unsigned long long)got, (unsigned long long)recorded);
  QCOMPARE(got, recorded);
}

}  // namespace

class TestDeterminism : public QObject {
  Q_OBJECT
 private slots:
  void thermalGrid() {
    for (int threads : {1, 2}) {
      std::vector<float> h = hills(160, 130);
      terrain::ThermalParams p;
      p.talusDegrees = 25.0;
      p.iterations = 200;
      terrain::erodeThermalGrid(h, 160, 130, {1.0, 1.0}, p, nullptr, nullptr, threads);
      Fnv f;
      f.vec(h);
      check("thermal grid", f.h, kThermalGrid);
    }
  }

  void hydraulicGrid() {
    for (int threads : {1, 2}) {
      std::vector<float> h = hills(160, 130);
      terrain::HydraulicParams p;
      p.iterations = 200;
      terrain::erodeHydraulicGrid(h, 160, 130, {1.0, 1.0}, p, nullptr, nullptr, threads);
      Fnv f;
      f.vec(h);
      check("hydraulic grid", f.h, kHydraulicGrid);
    }
  }

  // Through the tiled heightfield (window copy, mask, write-back).
  void erosionOnTerrain() {
    for (int threads : {1, 2}) {
      terrain::Terrain t = hillTerrain(300);
      terrain::HydraulicParams hp;
      hp.iterations = 60;
      terrain::erodeHydraulic(t.height, hp, terrain::ErosionMask::whole(t.height), nullptr, nullptr, threads);
      terrain::ThermalParams tp;
      tp.iterations = 60;
      terrain::erodeThermal(t.height, tp, terrain::ErosionMask::whole(t.height), nullptr, nullptr, threads);
      check("erosion on terrain", heightHash(t), kErosionTerrain);
    }
  }

  void paintRules() {
    for (int threads : {1, 2}) {
      terrain::Terrain t = hillTerrain(300);
      terrain::PaintRule grass;
      grass.layer = 1;
      grass.useSlope = true;
      grass.slopeMax = 12.0;
      terrain::PaintRule rock;
      rock.layer = 2;
      rock.useSlope = true;
      rock.slopeMin = 20.0;
      rock.slopeMax = 90.0;
      terrain::PaintRule snow;
      snow.layer = 3;
      snow.useAltitude = true;
      snow.altitudeMin = 315.0;
      snow.altitudeMax = 1e4;
      snow.strength = 0.7f;
      QVERIFY(terrain::applyPaintRules(t, {grass, rock, snow}, {}, nullptr, threads).ok());
      Fnv f;
      for (int l = 0; l < t.paint.layerCount(); ++l)
        for (int y = 0; y < 300; ++y)
          for (int x = 0; x < 300; ++x) {
            const uint16_t w = t.paint.raw(l, x, y);
            f.bytes(&w, sizeof w);
          }
      check("paint rules", f.h, kPaintRules);
    }
  }

  void decimation() {
    const mesh::MeshData in = bunny();
    for (double ratio : {0.5, 0.1, 0.01})
      for (unsigned threads : {1u, 2u}) {
        mesh::DecimateOptions o;
        o.targetRatio = ratio;
        o.threads = threads;
        const mesh::DecimateResult r = mesh::decimate(in, o);
        QVERIFY(r.ok());
        const uint64_t recorded = ratio == 0.5 ? kDecimate50 : ratio == 0.1 ? kDecimate10 : kDecimate1;
        check(qPrintable(QString("decimation to %1").arg(ratio)), meshHash(r.mesh), recorded);
      }
  }

 private:
  static constexpr uint64_t kThermalGrid = 0x39866b38168eaa9eull;
  static constexpr uint64_t kHydraulicGrid = 0xc2f70af625ac8da6ull;
  static constexpr uint64_t kErosionTerrain = 0xee94f7296e296fbeull;
  static constexpr uint64_t kPaintRules = 0x3b6d8d09148bde52ull;
  // Decimation changed on purpose (issue 11 item 4): after level 0's rounds
  // the regions merge pairwise and catch their strips up in parallel
  // (meshproc/region_levels.cpp), and a round's threshold is sampled from
  // the heap and the entries waiting beside it. Same Hausdorff on the bunny
  // at 50% and within 2% at 10% and 1% (docs/meshes.md, "Seventh round").
  static constexpr uint64_t kDecimate50 = 0xd7075b9ec32fbf98ull;
  static constexpr uint64_t kDecimate10 = 0x4c5c595bc7333becull;
  static constexpr uint64_t kDecimate1 = 0xe13228fa78973de0ull;
};

QTEST_GUILESS_MAIN(TestDeterminism)
#include "test_determinism.moc"
