// bench_collapse_schedule: our decimator (greedy heap, 2 threads and 1)
// against a prototype on meshoptimizer's schedule (pass_schedule.h: passes
// of independent collapses with our quadrics, placement and checks) and
// meshopt_simplify itself, on the bunny at the same triangle counts:
// wall time (median of interleaved runs) and Hausdorff measured by the
// same ErrorMeter. docs/meshes.md, "Ninth round", has what it showed.
//
//   bench_collapse_schedule [--bunny PATH] [--ratios 50,10,1] [--runs 7]
//                           [--pass-limit 1.5] [--lock ends|rings]
//                           [--placement optimal|endpoint] [--tile N]
//
// --tile N adds bench_decimate's synthetic scan tile (scan_terrain.h, N x N
// quads; 1580 is its 5M triangles) without its UVs, so that ours, which
// keeps UV seams, and the prototype, which has none, do the same job.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <meshoptimizer.h>

#include "bench/common/bench_util.h"
#include "meshproc/decimate.h"
#include "meshproc/error_metrics.h"
#include "bunny.h"
#include "pass_schedule.h"
#include "scan_terrain.h"

using namespace hs::mesh;
using hs::bench::median;
using hs::bench::nowSeconds;

int main(int argc, char** argv) {
  std::string bunnyPath = hs::bench::kBunnyPath;
  std::vector<double> ratios{50, 10, 1};
  int runs = 7, tileQuads = 0;
  hs::bench::PassScheduleOptions popt;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--bunny") bunnyPath = next();
    else if (a == "--runs") runs = std::max(1, std::atoi(next().c_str()));
    else if (a == "--pass-limit") popt.passLimit = std::atof(next().c_str());
    else if (a == "--lock") popt.lockOneRings = next() == "rings";
    else if (a == "--placement") popt.endpointPlacement = next() == "endpoint";
    else if (a == "--tile") tileQuads = std::atoi(next().c_str());
    else if (a == "--ratios") ratios = hs::bench::numberList(next());
    else {
      std::fprintf(stderr,
                   "usage: %s [--bunny PATH] [--ratios 50,10,1] [--runs 7] [--pass-limit 1.5] [--lock ends|rings] "
                   "[--placement optimal|endpoint] [--tile N]\n",
                   argv[0]);
      return 2;
    }
  }
  struct Dataset {
    std::string name;
    MeshData mesh;
    double samplesPerFace;
  };
  std::vector<Dataset> sets;
  {
    std::optional<MeshData> bunny = hs::bench::loadBunny(bunnyPath);
    if (!bunny) return 1;
    sets.push_back({"Stanford bunny", std::move(*bunny), 10.0});
  }
  if (tileQuads > 0) {
    MeshData t = hs::bench::scanTerrain(tileQuads, 500.0);
    t.uvs.clear();
    sets.push_back({"synthetic scan tile without UVs", std::move(t), 1.0});
  }
  for (const Dataset& set : sets) {
    const MeshData& in = set.mesh;
    ErrorOptions eo;
    eo.samplesPerFace = set.samplesPerFace;
    eo.seed = 1;
    const ErrorMeter meter(in, eo);

    std::printf("# Collapse schedules on the %s (%zu triangles, error: %g samples per face each way, seed 1): greedy heap vs passes\n",
                set.name.c_str(), in.triangleCount(), set.samplesPerFace);
    std::printf("prototype: pass limit %.2f, locks %s, placement %s; median of %d interleaved runs; load average %s\n\n",
                popt.passLimit, popt.lockOneRings ? "one-rings" : "both ends",
                popt.endpointPlacement ? "endpoint" : "optimal", runs, hs::bench::loadAverageLine().c_str());
    std::printf("| target | method | triangles | time s | time / meshopt | Hausdorff m | Hausdorff / meshopt |\n");
    std::printf("|---|---|---:|---:|---:|---:|---:|\n");
    std::vector<std::string> phaseRows;
    for (const double ratio : ratios) {
      DecimateOptions d;
      d.targetRatio = ratio / 100.0;
      std::vector<double> tOurs2, tOurs1, tPasses, tMeshopt;
      MeshData ours, passes, meshopt = in;
      hs::bench::PassScheduleStats st;
      std::vector<uint32_t> dst(in.indices.size());
      size_t n = 0;
      for (int i = 0; i < runs; ++i) {
        double t = nowSeconds();
        d.threads = 2;
        DecimateResult two = decimate(in, d);
        tOurs2.push_back(nowSeconds() - t);
        t = nowSeconds();
        d.threads = 1;
        DecimateResult one = decimate(in, d);
        tOurs1.push_back(nowSeconds() - t);
        if (!two.ok() || !one.ok() || two.mesh.indices != one.mesh.indices) {
          std::fprintf(stderr, "ours failed or differs between 1 and 2 threads\n");
          return 1;
        }
        ours = std::move(two.mesh);
        const size_t triangles = ours.triangleCount();
        st = {};
        t = nowSeconds();
        passes = hs::bench::decimateInPasses(in, triangles, popt, st);
        tPasses.push_back(nowSeconds() - t);
        t = nowSeconds();
        n = meshopt_simplify(dst.data(), in.indices.data(), in.indices.size(), &in.positions[0].x,
                             in.positions.size(), sizeof(glm::vec3), triangles * 3, 1e30f, 0, nullptr);
        tMeshopt.push_back(nowSeconds() - t);
      }
      meshopt.indices.assign(dst.begin(), dst.begin() + long(n));
      meshopt.submeshes = {{0, uint32_t(n), -1}};
      const double hMeshopt = meter.measure(meshopt).hausdorff, tm = median(tMeshopt);
      auto row = [&](const char* method, const MeshData& m, double t, bool peer) {
        const double h = peer ? hMeshopt : meter.measure(m).hausdorff;
        char tr[32] = "", hr[32] = "";
        if (!peer) std::snprintf(tr, sizeof tr, "%.2fx", t / tm), std::snprintf(hr, sizeof hr, "%.2fx", h / hMeshopt);
        std::printf("| %g%% | %s | %zu | %.4f | %s | %.3e | %s |\n", ratio, method, m.triangleCount(), t, tr, h, hr);
      };
      row("meshopt_simplify (1 thread)", meshopt, tm, true);
      row("ours (2 threads)", ours, median(tOurs2), false);
      row("ours (1 thread)", ours, median(tOurs1), false);
      row("passes prototype (1 thread)", passes, median(tPasses), false);
      char buf[512];
      std::snprintf(buf, sizeof buf,
                    "| %g%% | %d | %zu | %zu / %zu | %zu | %zu / %zu | %.4f / %.4f / %.4f / %.4f / %.4f |", ratio,
                    st.passes, st.evaluations, st.walked, st.tried, st.collapses, st.rejectedTopology,
                    st.rejectedGeometry, st.setup, st.lists, st.evaluate, st.sort, st.collapse);
      phaseRows.push_back(buf);
    }
    std::printf("\nThe prototype's last run:\n\n");
    std::printf("| target | passes | evaluations | candidates walked / tried | collapses | refused: topology / geometry | "
                "seconds: setup / face lists / evaluations / sort / collapses |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---|\n");
    for (const std::string& row : phaseRows) std::printf("%s\n", row.c_str());
    std::printf("\n");
  }
  return 0;
}
