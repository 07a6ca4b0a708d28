// The error report's cost: the closest-point queries that measure a
// decimated mesh against its original (meshproc/error_metrics.h), which
// took 95% of an import that decimates a 2M-triangle scan and builds its
// LODs. Three ways to answer the same queries, on the same sample points,
// one thread each, interleaved:
//   per point   ClosestPointBvh::closest with the previous hit as hint
//               (what the report did before closestMany),
//   per face    ClosestPointBvh::closestMany, a face's samples together
//               (what it does now),
//   CGAL        CGAL's AABB_tree::closest_point with its kd-tree of hints
//               (accelerate_distance_queries), the peer and an independent
//               check of every distance.
// Then the whole report (ErrorMeter::measure) on every thread, as an
// import runs it.
//
// With --convergence 1,2,5,...: instead, what the report's own
// approximation buys. The report samples the surfaces (its Hausdorff is a
// lower bound that rises with the rate); for each rate it prints the
// measure's time and its Hausdorff, mean and 95th percentile as shares of
// those at the densest rate listed, and the certified upper bound of the
// Hausdorff from that maximum (ErrorMeter::hausdorffUpperBound).
//
// usage: bench_error_measure [--quads N] [--ratios 50,10,1] [--runs K] [--samples-per-face S]
//                            [--skip-bunny] [--skip-tile] [--convergence 1,2,5,10,20,100]
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "bunny.h"
#include "core/parallel.h"
#include "meshproc/closest_point_bvh.h"
#include "meshproc/decimate.h"
#include "meshproc/error_metrics.h"
#include "meshproc/surface_sampling.h"
#include "scan_terrain.h"

using namespace hs;
using namespace hs::mesh;
using hs::bench::median;
using hs::bench::nowSeconds;

namespace {

using K = CGAL::Simple_cartesian<double>;
using CgalTriangles = std::vector<K::Triangle_3>;
using CgalTree = CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_triangle_primitive<K, CgalTriangles::const_iterator>>>;

// A direction's samples: every face's share (allocateSamples), placed by
// the report's own generator, so these are the report's points.
struct Samples {
  std::vector<uint64_t> first;
  std::vector<glm::dvec3> points;
};

Samples samplesOn(const MeshData& m, uint64_t total, uint64_t seed) {
  Samples s;
  s.first = allocateSamples(m, total);
  s.points.resize(s.first.back());
  for (size_t f = 0; f < m.triangleCount(); ++f)
    faceSamples(m, f, seed, glm::dvec3(0.0), std::span(s.points).subspan(s.first[f], s.first[f + 1] - s.first[f]));
  return s;
}

std::vector<double> perPoint(const ClosestPointBvh& bvh, const Samples& s) {
  std::vector<double> d(s.points.size());
  uint32_t hint = UINT32_MAX;
  for (size_t k = 0; k < s.points.size(); ++k) {
    const auto hit = bvh.closest(s.points[k], hint);
    hint = hit.face;
    d[k] = hit.distanceSq;
  }
  return d;
}

std::vector<double> perFace(const ClosestPointBvh& bvh, const Samples& s, ClosestPointBvh::ManyScratch& scratch) {
  std::vector<double> d(s.points.size());
  std::vector<ClosestPointBvh::Hit> hits;
  uint32_t hint = UINT32_MAX;
  for (size_t f = 0; f + 1 < s.first.size(); ++f) {
    const size_t n = s.first[f + 1] - s.first[f];
    if (n == 0) continue;
    hits.resize(n);
    hint = bvh.closestMany(std::span(s.points).subspan(s.first[f], n), hint, hits, scratch);
    for (size_t k = 0; k < n; ++k) d[s.first[f] + k] = hits[k].distanceSq;
  }
  return d;
}

std::vector<double> cgal(const CgalTree& tree, const Samples& s) {
  std::vector<double> d(s.points.size());
  for (size_t k = 0; k < s.points.size(); ++k) {
    const K::Point_3 q(s.points[k].x, s.points[k].y, s.points[k].z);
    d[k] = CGAL::squared_distance(q, tree.closest_point(q));
  }
  return d;
}

CgalTriangles cgalTriangles(const MeshData& m) {
  CgalTriangles t;
  t.reserve(m.triangleCount());
  auto p = [&](uint32_t i) {
    const glm::dvec3 v(m.positions[i]);
    return K::Point_3(v.x, v.y, v.z);
  };
  for (size_t f = 0; f < m.triangleCount(); ++f)
    t.emplace_back(p(m.indices[f * 3]), p(m.indices[f * 3 + 1]), p(m.indices[f * 3 + 2]));
  return t;
}

// The report at each sampling rate, against the densest one.
void convergence(const std::string& name, const MeshData& original, const std::vector<double>& ratios,
                 const std::vector<double>& rates) {
  for (double r : ratios) {
    DecimateOptions d;
    d.targetRatio = r;
    const DecimateResult dr = decimate(original, d);
    if (!dr.ok()) {
      std::fprintf(stderr, "%s at %g: %s\n", name.c_str(), r, dr.error.c_str());
      return;
    }
    std::vector<ErrorReport> reports;
    std::vector<HausdorffBound> bounds;
    std::vector<double> seconds;
    for (double rate : rates) {
      ErrorOptions eo;
      eo.samplesPerFace = rate;
      eo.maxSamples = UINT64_MAX;  // the rate as asked, past the report's cap
      const ErrorMeter meter(original, eo);
      const double t0 = nowSeconds();
      reports.push_back(meter.measure(dr.mesh));
      seconds.push_back(nowSeconds() - t0);
      bounds.push_back(meter.hausdorffUpperBound(dr.mesh, reports.back().hausdorff));
    }
    const ErrorReport& ref = reports.back();
    for (size_t i = 0; i < rates.size(); ++i) {
      const ErrorReport& e = reports[i];
      const HausdorffBound& h = bounds[i];
      std::printf("| %s | %g%% | %g | %llu | %.3f | %.4e | %.4f | %.4e | %.4f | %.4e | %.4f | %.4e | %.4f | %.3f | %llu |\n",
                  name.c_str(), r * 100.0, rates[i], static_cast<unsigned long long>(e.forward.samples + e.backward.samples),
                  seconds[i], e.hausdorff, e.hausdorff / ref.hausdorff, e.mean, e.mean / ref.mean, e.p95, e.p95 / ref.p95,
                  h.upper, h.upper / e.hausdorff, h.seconds, static_cast<unsigned long long>(h.pieces));
      std::fflush(stdout);
    }
  }
}

struct Row {
  double perPoint = 0, perFace = 0, cgal = 0;
};

// One direction: samples on `from`, queried against `to`, `runs` times each
// way, interleaved; prints one table row and returns the medians.
Row direction(const char* mesh, const char* ratio, const char* dir, const MeshData& from, const MeshData& to,
              uint64_t total, uint64_t seed, int runs) {
  const Samples s = samplesOn(from, total, seed);
  double t0 = nowSeconds();
  const ClosestPointBvh bvh(to, 1);
  const double oursBuild = nowSeconds() - t0;
  t0 = nowSeconds();
  const CgalTriangles tris = cgalTriangles(to);
  CgalTree tree(tris.begin(), tris.end());
  tree.accelerate_distance_queries();
  const double cgalBuild = nowSeconds() - t0;

  std::vector<double> tp, tf, tc;
  std::vector<double> dp, df, dc;
  ClosestPointBvh::ManyScratch scratch;
  for (int r = 0; r < runs; ++r) {
    t0 = nowSeconds();
    dp = perPoint(bvh, s);
    tp.push_back(nowSeconds() - t0);
    t0 = nowSeconds();
    scratch.scannedChunks = scratch.walkedChunks = 0;
    df = perFace(bvh, s, scratch);
    tf.push_back(nowSeconds() - t0);
    t0 = nowSeconds();
    dc = cgal(tree, s);
    tc.push_back(nowSeconds() - t0);
  }
  // Per face must give per point's distances bit for bit; CGAL's are
  // computed another way and agree to rounding.
  size_t differ = 0;
  double maxDev = 0, maxD = 0;
  for (size_t k = 0; k < dp.size(); ++k) {
    differ += dp[k] != df[k];
    maxDev = std::max(maxDev, std::abs(std::sqrt(dp[k]) - std::sqrt(dc[k])));
    maxD = std::max(maxD, std::sqrt(dp[k]));
  }
  Row row{median(tp), median(tf), median(tc)};
  const double n = double(s.points.size());
  const double scanned = double(scratch.scannedChunks) / double(std::max<size_t>(1, scratch.scannedChunks + scratch.walkedChunks));
  std::printf("| %s | %s | %s | %zu | %.3f | %.3f | %.3f | %.2f | %.2f | %.2fx | %.2fx | %.0f%% | %zu | %.1e | %.3e | %.3f / %.3f |\n",
              mesh, ratio, dir, s.points.size(), row.perPoint, row.perFace, row.cgal, n / row.perFace * 1e-6,
              n / row.cgal * 1e-6, row.perPoint / row.perFace, row.cgal / row.perFace, 100.0 * scanned, differ, maxDev,
              maxD, oursBuild, cgalBuild);
  std::fflush(stdout);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  int quads = 1000, runs = 3;
  double samplesPerFace = 10.0;
  std::vector<double> ratios = {0.5, 0.1, 0.01};
  std::vector<double> rates;
  bool bunny = true, tile = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--quads") quads = std::atoi(next().c_str());
    else if (a == "--runs") runs = std::max(1, std::atoi(next().c_str()));
    else if (a == "--samples-per-face") samplesPerFace = std::atof(next().c_str());
    else if (a == "--skip-bunny") bunny = false;
    else if (a == "--skip-tile") tile = false;
    else if (a == "--ratios") ratios = hs::bench::numberList(next(), 100.0);
    else if (a == "--convergence") rates = hs::bench::numberList(next());
    else {
      std::fprintf(stderr,
                   "usage: %s [--quads N] [--ratios 50,10,1] [--runs K] [--samples-per-face S] [--skip-bunny] "
                   "[--skip-tile] [--convergence 1,2,5,10,20,100]\n",
                   argv[0]);
      return 2;
    }
  }

  struct Input {
    std::string name;
    MeshData mesh;
  };
  std::vector<Input> inputs;
  if (bunny) {
    if (auto m = hs::bench::loadBunny(hs::bench::kBunnyPath)) inputs.push_back({"bunny", std::move(*m)});
    else return 1;
  }
  if (tile) inputs.push_back({"scan tile " + std::to_string(2 * quads * quads / 1000) + "k", hs::bench::scanTerrain(quads, 500.0)});

  if (!rates.empty()) {
    std::sort(rates.begin(), rates.end());
    std::printf("# Error report: its sampling rate against its time (ErrorMeter::measure, %u threads)\n",
                availableThreads());
    std::printf("load average at start: %s\n\n", hs::bench::loadAverageLine().c_str());
    std::printf("Shares are of the densest rate's figures (%g samples per original face each way, no cap); each "
                "mesh decimated by ours.\n\n", rates.back());
    std::printf("The certified upper bound (ErrorMeter::hausdorffUpperBound) starts from each row's Hausdorff: no "
                "point of either surface is further from the other.\n\n");
    std::printf("| mesh | target | samples per face | samples (both ways) | measure s | Hausdorff m | of densest | "
                "mean m | of densest | p95 m | of densest | upper bound m | of the row's Hausdorff | bound s | pieces "
                "|\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const Input& in : inputs) convergence(in.name, in.mesh, ratios, rates);
    return 0;
  }

  std::printf("# Error report queries: per point vs per face (closestMany) vs CGAL AABB_tree (1 thread each)\n");
  std::printf("load average at start: %s\n\n", hs::bench::loadAverageLine().c_str());
  std::printf("%g samples per original face in each direction, %d interleaved runs, medians; both decimated by ours.\n\n",
              samplesPerFace, runs);
  std::printf("| mesh | target | direction | points | per point s | per face s | CGAL s | per face Mpts/s | CGAL Mpts/s "
              "| per point / per face | CGAL / per face | chunks scanned | distances differing (per point vs per face) | "
              "max abs(ours - CGAL) m | max distance m | build s: ours / CGAL |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");

  struct Whole {
    std::string mesh, ratio;
    double seconds = 0, queryShare = 0;
  };
  std::vector<Whole> whole;
  for (const Input& in : inputs) {
    const uint64_t total = uint64_t(std::llround(samplesPerFace * double(in.mesh.triangleCount())));
    ErrorOptions eo;
    eo.samplesPerFace = samplesPerFace;
    const ErrorMeter meter(in.mesh, eo);
    for (double r : ratios) {
      DecimateOptions d;
      d.targetRatio = r;
      const DecimateResult dr = decimate(in.mesh, d);
      if (!dr.ok()) {
        std::fprintf(stderr, "%s at %g: %s\n", in.name.c_str(), r, dr.error.c_str());
        return 1;
      }
      char ratio[32];
      std::snprintf(ratio, sizeof ratio, "%g%%", r * 100.0);
      // The report's two directions (seeds as ErrorMeter draws them).
      const Row f = direction(in.name.c_str(), ratio, "original -> result", in.mesh, dr.mesh, total, eo.seed, runs);
      const Row b = direction(in.name.c_str(), ratio, "result -> original", dr.mesh, in.mesh, total, eo.seed + 1, runs);
      std::vector<double> t;
      for (int k = 0; k < runs; ++k) {
        const double t0 = nowSeconds();
        const ErrorReport e = meter.measure(dr.mesh);
        t.push_back(nowSeconds() - t0);
        if (e.hausdorff <= 0) std::fprintf(stderr, "note: zero Hausdorff for %s at %s\n", in.name.c_str(), ratio);
      }
      // The share of the whole report that the queries are, had they run
      // on every thread as the report runs them (one thread here).
      whole.push_back({in.name, ratio, median(t), (f.perFace + b.perFace) / double(availableThreads()) / median(t)});
    }
  }
  std::printf("\nThe whole report (ErrorMeter::measure, %u threads: the queries above plus the result's BVH, its "
              "polylines, normals and UVs, and the statistics):\n\n| mesh | target | measure s | queries' share (est.) |\n|---|---|---:|---:|\n",
              availableThreads());
  for (const Whole& w : whole)
    std::printf("| %s | %s | %.3f | %.0f%% |\n", w.mesh.c_str(), w.ratio.c_str(), w.seconds, 100.0 * w.queryShare);
  return 0;
}
