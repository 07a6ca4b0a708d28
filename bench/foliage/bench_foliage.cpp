// Foliage on the CPU: the rule-based scatter of 1M instances over a 4097^2
// terrain with slope, altitude and paint-layer filters (target: under 2 s on
// 2 cores), a scatter on a 1M-triangle scan, paint and erase dabs at
// radius 20 m among 10k instances (target: under 16 ms, the editor's
// frame), the save after one stroke in a scene of 1M instances (only the
// dirty cells), with bytes per instance in memory and in the file, and the
// ground following after a sculpt stroke under 1M instances.
//
//   build/bench/foliage/bench_foliage [--quick]
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "core/parallel.h"
#include "foliage/ground_follow.h"
#include "foliage/tools.h"
#include "terrain/noise.h"
#include "terrain/stroke.h"

using namespace hs::foliage;
using hs::bench::median;
using hs::bench::nowSeconds;
namespace ht = hs::terrain;

namespace {

ht::Terrain hills(int n) {
  ht::HeightfieldDesc d;
  d.samplesX = d.samplesY = n;
  d.sizeMetres = {double(n - 1), double(n - 1)};
  d.origin = {500000.0, 4400000.0, 0.0};  // UTM, as the valley's
  ht::Terrain t = ht::Terrain::create(d).take();
  ht::FractalNoise fn;
  fn.seed = 7;
  fn.scale = 400.0;
  fn.octaves = 6;
  ht::FractalNoise layerNoise;
  layerNoise.seed = 3;
  layerNoise.scale = 150.0;
  std::vector<float> row(static_cast<size_t>(n)), lrow(static_cast<size_t>(n));
  t.paint.prepareBlend(t.height.bounds(), 1);
  for (int y = 0; y < n; ++y) {
    fn.row(0.0, 1.0, double(y), n, row.data());
    layerNoise.row(0.0, 1.0, double(y), n, lrow.data());
    for (int x = 0; x < n; ++x) {
      t.height.heights().set(x, y, 300.0f + 120.0f * row[size_t(x)]);
      if (lrow[size_t(x)] > 0.0f) t.paint.blendPrepared(x, y, 1, std::min(1.0f, 3.0f * lrow[size_t(x)]));
    }
  }
  t.height.updateAllBounds();
  return t;
}

// The share of the terrain's area the type's filters keep (sampled).
double keptShare(const FoliageType& ft, const ht::Terrain& t) {
  std::mt19937_64 rng(1);
  const glm::dvec2 o(t.height.origin());
  std::uniform_real_distribution<double> u(0.0, t.height.sizeMetres().x);
  const int layer = terrainLayerIndex(t, ft.layer);
  int kept = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const glm::dvec2 p = o + glm::dvec2(u(rng), u(rng));
    const auto sp = terrainSurface(t.height, p);
    kept += sp && passesFilters(ft, *sp, terrainLayerWeight(t, layer, p));
  }
  return double(kept) / n;
}

size_t memoryBytes(const FoliageStore& s) {
  size_t b = 0;
  for (const auto& [k, c] : s.cells()) {
    b += sizeof(CellKey) + sizeof(Cell) + 32;  // the map's node, roughly
    for (const Run& r : c.runs) b += sizeof(Run) + r.items.capacity() * sizeof(PackedInstance);
  }
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const int n = quick ? 2049 : 4097;
  const double scale = quick ? 0.25 : 1.0;  // instance counts scale with the area
  std::printf("Foliage on the CPU: %s, load average %.2f\n", hs::bench::threadsText().c_str(), hs::bench::loadAverage());
  double t0 = nowSeconds();
  ht::Terrain t = hills(n);
  std::printf("terrain %dx%d at 1 m spacing (fractal hills 180..420 m, paint layer 1 on about half), made in %.1f s\n\n", n,
              n, nowSeconds() - t0);
  Ground g{&t, {}};

  // --- scatter 1M with filters -----------------------------------------------------------------
  FoliageType pine;
  pine.name = "Pine";
  pine.mesh = "pine";
  pine.spacing = 1.0;
  pine.slopeDeg = {0.0, 35.0};
  pine.altitude = {0.0, 400.0};
  pine.layer = t.paint.material(1).name;
  pine.layerWeight = {0.1, 1.0};
  pine.alignToNormal = true;
  pine.scale = {0.8, 1.3};
  const double share = keptShare(pine, t);
  const double areaHa = double(n - 1) * double(n - 1) / 1e4;
  pine.densityPerHa = 1.035e6 * scale / (areaHa * share);  // the Poisson refusals take ~3%
  std::printf("scatter: density %.0f/ha, spacing %.1f m, slope 0-35 deg, altitude 0-400 m, layer weight 0.1-1 "
              "(the filters keep %.1f%% of the area)\n",
              pine.densityPerHa, pine.spacing, share * 100.0);
  std::printf("%-34s %8s %10s %10s %12s %10s\n", "operation", "threads", "seconds", "placed", "per second", "vs target");
  FoliageStore big;
  for (unsigned threads : {1u, 2u}) {
    FoliageStore s;
    std::vector<std::string> m;
    s.addType(pine, m);
    t0 = nowSeconds();
    const EditResult r = scatter(s, g, {0}, 42, std::nullopt, threads);
    const double dt = nowSeconds() - t0;
    std::printf("%-34s %8u %10.3f %10zu %12.0f %9.2fx\n", "scatter on the terrain", threads, dt, r.stats.placed,
                double(r.stats.placed) / dt, dt / 2.0);
    std::printf("    candidates %zu: off the terrain/region %zu, filtered %zu, too close after %d throws %zu\n",
                r.stats.candidates, r.stats.outside, r.stats.filtered, kAttempts, r.stats.spacingRejected);
    if (threads == 2) big = std::move(s);
  }

  // --- scatter on a 1M-triangle scan --------------------------------------------------------------
  {
    const int cells = quick ? 354 : 708;  // 2 * 708^2 = 1.0M triangles
    hs::mesh::MeshData scan;
    scan.origin = {512000.0, 4410000.0, 250.0};
    ht::FractalNoise fn;
    fn.seed = 9;
    fn.scale = 120.0;
    const double size = 1000.0 * std::sqrt(scale);
    for (int y = 0; y <= cells; ++y)
      for (int x = 0; x <= cells; ++x) {
        const double px = size * x / cells, py = size * y / cells;
        scan.positions.emplace_back(float(px), float(py), 60.0f * fn.at(px, py));
      }
    for (int y = 0; y < cells; ++y)
      for (int x = 0; x < cells; ++x) {
        const uint32_t a = uint32_t(y * (cells + 1) + x), b = a + 1, c = a + uint32_t(cells + 1) + 1,
                       d = a + uint32_t(cells + 1);
        scan.indices.insert(scan.indices.end(), {a, b, c, a, c, d});
      }
    t0 = nowSeconds();
    MeshGround mg(scan);
    const double build = nowSeconds() - t0;
    Ground gm{nullptr, {&mg}};
    FoliageType shrub;
    shrub.name = "Shrub";
    shrub.mesh = "shrub";
    shrub.spacing = 0.5;
    shrub.surface = SurfaceFilter::Meshes;
    shrub.slopeDeg = {0.0, 45.0};
    shrub.alignToNormal = true;
    shrub.densityPerHa = 10000.0;
    for (unsigned threads : {1u, 2u}) {
      FoliageStore s;
      std::vector<std::string> m;
      s.addType(shrub, m);
      t0 = nowSeconds();
      const EditResult r = scatter(s, gm, {0}, 5, std::nullopt, threads);
      const double dt = nowSeconds() - t0;
      std::printf("%-34s %8u %10.3f %10zu %12.0f\n", "scatter on a 1M-triangle scan", threads, dt, r.stats.placed,
                  double(r.stats.placed) / dt);
    }
    std::printf("    (%zu triangles; the scan's BVH and XY bins built once in %.3f s, not counted)\n",
                mg.triangleCount(), build);
  }

  // --- dabs among 10k instances --------------------------------------------------------------------
  {
    FoliageStore s;
    std::vector<std::string> m;
    FoliageType a = pine;
    a.name = "A";
    a.layer.clear();
    a.slopeDeg = {0, 90};
    a.altitude = {-1e5, 1e5};
    a.densityPerHa = 1100.0;
    s.addType(a, m);
    FoliageType b = a;
    b.name = "B";
    b.densityPerHa = 2000.0;
    b.spacing = 1.0;
    s.addType(b, m);
    const glm::dvec2 o = glm::dvec2(t.height.origin()) + 1000.0;
    scatter(s, g, {0}, 1, Region2::rect(o, o + 300.0));
    std::printf("\ndabs at radius 20 m among %zu instances (type A over 300x300 m); median of 60 dabs, each undone\n",
                s.instanceCount());
    std::printf("%-34s %10s %10s %10s %10s\n", "dab", "ms", "p90 ms", "changed", "vs 16 ms");
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(40.0, 260.0);
    struct Case {
      const char* name;
      int kind;
    };
    for (const Case c : {Case{"paint B (a new type)", 0}, Case{"paint A (over 10k of A)", 1}, Case{"erase all", 2},
                         Case{"select (brush)", 3}}) {
      std::vector<double> ms;
      double changed = 0;
      for (int i = 0; i < 60; ++i) {
        const Region2 dab = Region2::disc(o + glm::dvec2(u(rng), u(rng)), 20.0);
        t0 = nowSeconds();
        EditResult r;
        size_t sel = 0;
        if (c.kind <= 1) {
          PaintParams p;
          p.region = dab;
          p.types = {uint16_t(c.kind == 0 ? 1 : 0)};
          p.seed = uint64_t(i);
          r = paint(s, g, p);
        } else if (c.kind == 2) {
          r = erase(s, dab);
        } else {
          sel = selectRegion(s, dab).size();
        }
        ms.push_back((nowSeconds() - t0) * 1e3);
        changed += double(r.stats.placed + r.stats.removed + sel);
        r.undo.swap(s);
      }
      std::printf("%-34s %10.3f %10.3f %10.0f %9.3fx\n", c.name, median(ms), hs::bench::percentile(ms, 0.9),
                  changed / 60.0, median(ms) / 16.0);
    }
  }

  // --- ground following ------------------------------------------------------------------------------
  {
    std::printf("\nground following under the %zu-instance scatter (the instances on the changed cells move,\n"
                "those over holes go); the terrain edit itself is not timed\n", big.instanceCount());
    std::printf("%-34s %10s %10s %10s %12s\n", "edit", "samples", "checked", "moved", "follow ms");
    for (const double radius : {20.0, 64.0}) {
      const ht::Heightfield before = t.height.clone();
      ht::BrushSettings bs;
      bs.tool = ht::BrushTool::Raise;
      bs.radius = radius;
      bs.strength = 2.0f;
      ht::Stroke stroke(t, bs);
      for (int i = 0; i <= 8; ++i) stroke.moveTo({1500.0 * scale + 10.0 * radius * i / 8.0, 1500.0 * scale});
      const ht::Region changed = stroke.changed();
      stroke.finish();
      FollowStats fs;
      t0 = nowSeconds();
      FoliageUndo undo = followGround(big, before, t.height, changed, &fs);
      const double ms = (nowSeconds() - t0) * 1e3;
      char name[64];
      std::snprintf(name, sizeof name, "raise stroke, radius %.0f m", radius);
      std::printf("%-34s %10zu %10zu %10zu %12.3f\n", name, changed.samples(), fs.checked, fs.moved, ms);
      undo.swap(big);  // back as it was (the terrain keeps the stroke)
    }
  }

  // --- saving ----------------------------------------------------------------------------------------
  {
    std::printf("\nsaving the %zu-instance scatter (%zu cells of 64 m)\n", big.instanceCount(), big.cellCount());
    std::printf("%-34s %10s %10s %12s %12s\n", "save", "cells", "seconds", "bytes", "bytes/inst");
    t0 = nowSeconds();
    const SaveSet all = big.dirty();
    double dt = nowSeconds() - t0;
    big.markSaved();
    std::printf("%-34s %10zu %10.3f %12zu %12.2f\n", "first save (every cell)", all.write.size(), dt, all.bytes(),
                double(all.bytes()) / double(big.instanceCount()));
    // One stroke: 12 dabs of radius 20 m along a line.
    FoliageType grass = pine;
    grass.name = "Grass";
    grass.layer.clear();
    grass.densityPerHa = 5000.0;
    grass.spacing = 0.5;
    std::vector<std::string> m;
    big.addType(grass, m);
    const glm::dvec2 o = glm::dvec2(t.height.origin()) + 700.0;
    size_t placed = 0;
    for (int i = 0; i < 12; ++i) {
      PaintParams p;
      p.region = Region2::disc(o + glm::dvec2(8.0 * i, 3.0 * i), 20.0);
      p.types = {1};
      p.seed = uint64_t(i);
      placed += paint(big, g, p).stats.placed;
    }
    t0 = nowSeconds();
    const SaveSet stroke = big.dirty();
    dt = nowSeconds() - t0;
    std::printf("%-34s %10zu %10.4f %12zu %12s\n", "save after one stroke (dirty only)", stroke.write.size(), dt,
                stroke.bytes(), "");
    std::printf("    (the stroke: 12 dabs, %zu instances placed; the blobs of its cells are all a save writes)\n", placed);
    std::printf("\nbytes per instance: %.2f in memory (16-byte records + cells), %.2f in the file (deflated cells)\n",
                double(memoryBytes(big)) / double(big.instanceCount()),
                double(all.bytes()) / double(big.instanceCount() - placed));
  }
  return 0;
}
