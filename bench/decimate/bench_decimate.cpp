// Decimation benchmark: error vs triangle count vs time, our decimator side
// by side with meshoptimizer's meshopt_simplify (same input, same triangle
// counts) and OpenMesh's stock DecimaterT + ModQuadricT, in one run, with
// ratios; on the Stanford bunny, a generated quad-dominant scan (32k
// triangulated quads, UV seams, fins) and a synthetic 5M-triangle scan
// tile. Blender's Decimate and MeshLab's quadric edge collapse run as peers
// on the quad scan at every ratio and on the bunny at 10% (peers.h; skipped
// with a note where not installed).
// Errors come from the project's error report (seeded surface sampling,
// symmetric Hausdorff). "ours + refine" is our result after the minimax
// vertex refinement an import runs (max_error_refine.h; its time is the
// decimation's median plus the refinement's median over the same runs).
// Also draws the error-vs-time curves as a PNG.
//
//   bench_decimate [--bunny PATH] [--terrain-quads 1580] [--runs 5]
//                  [--terrain-samples 1] [--stock-terrain 0.1|all|none]
//                  [--threads 2] [--plot bench_decimate.png] [--skip-terrain] [--skip-bunny]
//                  [--terrain-runs 3] [--ratios 50,25,10,5,1] [--no-error] [--no-stock]
//                  [--faces-per-region N] [--skip-quad] [--no-peers] [--work-dir /tmp] [--quad-no-uv] [--pause S] [--meshopt-huge-pages]
//                  [--quad-seed 11] [--where-max] [--bound] [--hard-quad] [--hard-quad-irregular] [--quad-object]
//                  (our output's content hash goes to stderr)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>
#include <algorithm>

#include <meshoptimizer.h>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include "bench/common/bench_util.h"
#include "bench/common/plot.h"
#include "mesh/weld.h"
#include "core/large_pages.h"
#include "meshproc/decimate.h"
#include "meshproc/decimate_trace.h"
#include "meshproc/closest_point_bvh.h"
#include "meshproc/error_metrics.h"
#include "meshproc/max_error_refine.h"
#include "bunny.h"
#include "peers.h"
#include "quad_object.h"
#include "quad_scan.h"
#include "scan_terrain.h"

using namespace hs::mesh;
using Clock = std::chrono::steady_clock;
using hs::bench::median;

namespace {

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }
// CPU seconds of the process (ours: both threads) or of this thread
// (meshopt runs on it alone; the scheduler's workers may still spin after
// our run and would be counted in the process's time). The load-independent
// figure beside the wall times on a shared machine.
double cpuSeconds(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// --meshopt-huge-pages: meshopt_simplify's allocations from the same
// huge-page allocator as our large arrays (core/large_pages.h), so that the
// two are compared with the same cost of first touches. meshopt frees by
// pointer only: the sizes are kept here.
std::unordered_map<void*, size_t> gMeshoptBlocks;
void* meshoptAllocate(size_t bytes) {
  void* p = hs::allocateLarge(bytes);
  gMeshoptBlocks[p] = bytes;
  return p;
}
void meshoptDeallocate(void* p) {
  const auto it = gMeshoptBlocks.find(p);
  if (it == gMeshoptBlocks.end()) return;
  hs::freeLarge(p, it->second);
  gMeshoptBlocks.erase(it);
}

struct Row {
  std::string method;
  double ratio = 0;
  size_t triangles = 0;
  double time = 0;
  double cpu = 0;  // median CPU seconds (ours and meshopt; 0: not measured)
  ErrorReport error;
  double buildTime = 0;  // stock OpenMesh: building its mesh (not in `time`)
  DecimateReport report;  // ours: the phases of the best run
  double errorTime = 0;   // measuring the error (not part of `time`)
};

MeshData withIndices(const MeshData& base, std::vector<uint32_t> indices) {
  MeshData m;
  m.origin = base.origin;
  m.positions = base.positions;
  m.uvs = base.uvs;
  m.materials = base.materials;
  m.indices = std::move(indices);
  m.submeshes.push_back({0, uint32_t(m.indices.size()), base.submeshes.empty() ? -1 : base.submeshes[0].material});
  return m;
}

// Ours and meshopt_simplify at the same triangle count, their runs
// interleaved (ours, meshopt, ours, ...) so both see the same load on a
// shared machine; times are medians. Ours must give the same mesh on every
// run (checked: deterministic output).
size_t gFacesPerRegion = 0;  // --faces-per-region (0: the decimator's default)
double gPause = 0;           // --pause S: seconds of sleep before every timed run (see runPair)

void runPair(const MeshData& in, double ratio, int runs, unsigned threads, Row& ours, MeshData& oursOut, Row& meshopt,
             MeshData& meshoptOut) {
  ours = Row{};
  ours.method = "ours (" + std::to_string(threads) + " threads)";
  ours.ratio = ratio;
  meshopt = Row{};
  meshopt.method = "meshopt_simplify (1 thread)";
  meshopt.ratio = ratio;
  DecimateOptions o;
  o.targetRatio = ratio;
  o.threads = threads;
  if (gFacesPerRegion) o.facesPerRegion = gFacesPerRegion;
  std::vector<double> cOurs, cMeshopt, fOurs, fMeshopt;
  std::vector<double> tOurs, tMeshopt, tSetup, tRegions, tLastRegion, tOutput;
  std::vector<uint32_t> dst(in.indices.size());
  size_t n = 0;
  for (int i = 0; i < runs; ++i) {
    if (gPause > 0) std::this_thread::sleep_for(std::chrono::duration<double>(gPause));
    const double c0 = cpuSeconds(CLOCK_PROCESS_CPUTIME_ID);
    const long f0 = DecimateTrace::minorFaults();
    const auto t0 = Clock::now();
    DecimateResult d = decimate(in, o);
    fOurs.push_back(double(DecimateTrace::minorFaults() - f0));
    const double t = seconds(t0, Clock::now());
    cOurs.push_back(cpuSeconds(CLOCK_PROCESS_CPUTIME_ID) - c0);
    if (!d.ok()) {
      std::fprintf(stderr, "decimate failed: %s\n", d.error.c_str());
      std::exit(1);
    }
    tOurs.push_back(t);
    tSetup.push_back(d.report.secondsSetup), tRegions.push_back(d.report.secondsRegions);
    tLastRegion.push_back(d.report.secondsLastRegion), tOutput.push_back(d.report.secondsOutput);
    if (i == 0) {
      ours.report = d.report;
      oursOut = std::move(d.mesh);
    } else if (d.mesh.indices != oursOut.indices || d.mesh.positions != oursOut.positions) {
      std::fprintf(stderr, "ours: run %d gave a different mesh than run 0 (not deterministic)\n", i);
      std::exit(1);
    }
    const size_t triangles = oursOut.triangleCount();
    if (gPause > 0) std::this_thread::sleep_for(std::chrono::duration<double>(gPause));
    const double c1 = cpuSeconds(CLOCK_THREAD_CPUTIME_ID);
    const long f1 = DecimateTrace::minorFaults();
    const auto t1 = Clock::now();
    n = meshopt_simplify(dst.data(), in.indices.data(), in.indices.size(), &in.positions[0].x, in.positions.size(),
                         sizeof(glm::vec3), triangles * 3, 1e30f, 0, nullptr);
    fMeshopt.push_back(double(DecimateTrace::minorFaults() - f1));
    tMeshopt.push_back(seconds(t1, Clock::now()));
    cMeshopt.push_back(cpuSeconds(CLOCK_THREAD_CPUTIME_ID) - c1);
  }
  {
    // Content hash of our output on stderr: optimisations that must not
    // change the result are checked against it.
    uint64_t h = 1469598103934665603ull;
    auto mixIn = [&](const void* data, size_t bytes) {
      const auto* b = static_cast<const unsigned char*>(data);
      for (size_t i = 0; i < bytes; ++i) h = (h ^ b[i]) * 1099511628211ull;
    };
    mixIn(oursOut.indices.data(), oursOut.indices.size() * sizeof(uint32_t));
    mixIn(oursOut.positions.data(), oursOut.positions.size() * sizeof(glm::vec3));
    std::fprintf(stderr, "ours %g%%: %zu triangles, output hash %016llx\n", ratio * 100, oursOut.triangleCount(),
                 (unsigned long long)h);
  }
  ours.time = median(tOurs);
  ours.cpu = median(cOurs);
  meshopt.cpu = median(cMeshopt);
  // The minima too (stderr): under load the medians move by tens of per
  // cent from run to run, the least CPU time of many runs much less.
  std::fprintf(stderr, "ours %g%%: CPU s min %.4f median %.4f, meshopt min %.4f median %.4f (%zu runs)\n", ratio * 100,
               *std::min_element(cOurs.begin(), cOurs.end()), ours.cpu,
               *std::min_element(cMeshopt.begin(), cMeshopt.end()), meshopt.cpu, cOurs.size());
  std::fprintf(stderr, "ours %g%%: minor page faults median %.0f, meshopt %.0f\n", ratio * 100, median(fOurs), median(fMeshopt));
  ours.triangles = oursOut.triangleCount();
  ours.report.secondsSetup = median(tSetup), ours.report.secondsRegions = median(tRegions);
  ours.report.secondsLastRegion = median(tLastRegion), ours.report.secondsOutput = median(tOutput);
  meshopt.time = median(tMeshopt);
  dst.resize(n);
  meshopt.triangles = n / 3;
  meshoptOut = withIndices(in, std::move(dst));
}

Row runStock(const MeshData& in, size_t triangles, double ratio, MeshData& out) {
  using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;
  Row r;
  r.method = "OpenMesh DecimaterT+ModQuadricT";
  r.ratio = ratio;
  const auto t0 = Clock::now();
  Mesh mesh;
  mesh.reserve(in.positions.size(), in.indices.size() / 2, in.indices.size() / 3);
  std::vector<Mesh::VertexHandle> vh;
  vh.reserve(in.positions.size());
  for (const auto& p : in.positions) vh.push_back(mesh.add_vertex(Mesh::Point(p.x, p.y, p.z)));
  for (size_t i = 0; i < in.indices.size(); i += 3)
    mesh.add_face(vh[in.indices[i]], vh[in.indices[i + 1]], vh[in.indices[i + 2]]);
  const auto t1 = Clock::now();
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
  dec.add(quadric);
  dec.initialize();
  dec.decimate_to_faces(0, triangles);
  mesh.garbage_collection();
  const auto t2 = Clock::now();
  r.buildTime = seconds(t0, t1);
  r.time = seconds(t1, t2);
  std::vector<uint32_t> idx;
  MeshData m;
  m.origin = in.origin;
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    m.positions.emplace_back(p[0], p[1], p[2]);
  }
  for (auto f : mesh.faces())
    for (auto v : mesh.fv_range(f)) m.indices.push_back(uint32_t(v.idx()));
  m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
  r.triangles = m.triangleCount();
  out = std::move(m);
  return r;
}

// --where-max: where the largest distances of `result` from `original`
// are, each way (vertices and face centres; in the original's local frame).
void printWorst(const MeshData& original, const MeshData& result, const char* what) {
  const glm::dvec3 shift = result.origin - original.origin;
  for (int dir = 0; dir < 2; ++dir) {
    const MeshData& from = dir == 0 ? original : result;
    const MeshData& to = dir == 0 ? result : original;
    const glm::dvec3 toLocal = dir == 0 ? -shift : shift;  // from's local frame -> to's
    ClosestPointBvh bvh(to);
    struct Worst {
      double d;
      glm::dvec3 p;
    };
    std::vector<Worst> worst;
    auto test = [&](const glm::dvec3& p) {
      const auto hit = bvh.closest(p + toLocal);
      worst.push_back({std::sqrt(hit.distanceSq), p + (dir == 0 ? glm::dvec3(0.0) : shift)});
    };
    for (const auto& v : from.positions) test(glm::dvec3(v));
    for (size_t f = 0; f < from.triangleCount(); ++f)
      test((glm::dvec3(from.positions[from.indices[3 * f]]) + glm::dvec3(from.positions[from.indices[3 * f + 1]]) +
            glm::dvec3(from.positions[from.indices[3 * f + 2]])) / 3.0);
    std::partial_sort(worst.begin(), worst.begin() + std::min<ptrdiff_t>(5, ptrdiff_t(worst.size())), worst.end(),
                      [](const Worst& a, const Worst& b) { return a.d > b.d; });
    for (size_t k = 0; k < std::min<size_t>(5, worst.size()); ++k)
      std::printf("|  | %s %s: %.3e m at (%.3f, %.3f, %.3f) | | | | | | | | | | | | | |\n", what,
                  dir == 0 ? "original->result" : "result->original", worst[k].d, worst[k].p.x, worst[k].p.y,
                  worst[k].p.z);
  }
}

void printHeader(const char* name, const MeshData& m, double samplesPerFace) {
  std::printf("\n## %s: %zu triangles, %zu vertices (error: %.0f samples per original face each way, seed 1)\n\n",
              name, m.triangleCount(), m.vertexCount(), samplesPerFace);
  std::printf("| target | method | triangles | time s | CPU s | input Mtri/s | Hausdorff m | Hausdorff / diag | mean m | RMS m | flips | time / meshopt | Hausdorff / meshopt | phases s: setup / regions / last region / output | error measure s |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|\n");
}

void printRow(const Row& r, const MeshData& in, const Row* meshopt) {
  char timeRatio[32] = "", hausRatio[32] = "";
  if (meshopt && meshopt != &r) {
    std::snprintf(timeRatio, sizeof timeRatio, "%.2fx", r.time / meshopt->time);
    if (meshopt->error.hausdorff > 0)  // not measured with --no-error
      std::snprintf(hausRatio, sizeof hausRatio, "%.2fx", r.error.hausdorff / meshopt->error.hausdorff);
  }
  char phases[96] = "";
  if (r.report.trianglesIn)
    std::snprintf(phases, sizeof phases, "%.3f / %.3f / %.3f / %.3f", r.report.secondsSetup, r.report.secondsRegions,
                  r.report.secondsLastRegion, r.report.secondsOutput);
  char cpu[32] = "";
  if (r.cpu > 0) std::snprintf(cpu, sizeof cpu, "%.4f", r.cpu);
  std::printf("| %g%% | %s | %zu | %.4f | %s | %.2f | %.3e | %.3e | %.3e | %.3e | %zu | %s | %s | %s | %.2f |\n", r.ratio * 100,
              r.method.c_str(), r.triangles, r.time, cpu, double(in.triangleCount()) / r.time / 1e6, r.error.hausdorff,
              r.error.rel(r.error.hausdorff), r.error.mean, r.error.rms, r.error.flippedNormals, timeRatio, hausRatio,
              phases, r.errorTime);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::string bunnyPath = hs::bench::kBunnyPath;
  std::string plotPath = "bench_decimate.png", stockTerrain = "0.1";
  int terrainQuads = 1580, runs = 5, terrainRuns = 3;
  bool measureErrors = true;
  std::vector<double> ratios = {0.5, 0.25, 0.1, 0.05, 0.01};
  double terrainSamples = 1.0;
  unsigned threads = 2;
  bool skipTerrain = false, skipBunny = false, noStock = false, skipQuad = false, noPeers = false, hardQuad = false,
       hardIrregular = false, quadObject = false;
  std::string workDir = "/tmp";
  bool quadNoUv = false;  // the quad scan without UVs: what its seams cost
  bool whereMax = false;
  bool bounds = false;  // --bound: each measured row's certified Hausdorff bracket too
  uint64_t quadSeed = 11;  // --quad-seed: another relief and noise of the same kind (is a lead a fluke?)
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (a == "--bunny") bunnyPath = next();
    else if (a == "--terrain-quads") terrainQuads = std::atoi(next().c_str());
    else if (a == "--runs") runs = std::max(1, std::atoi(next().c_str()));
    else if (a == "--terrain-runs") terrainRuns = std::max(1, std::atoi(next().c_str()));
    else if (a == "--no-error") measureErrors = false;
    else if (a == "--ratios") ratios = hs::bench::numberList(next(), 100.0);
    else if (a == "--terrain-samples") terrainSamples = std::atof(next().c_str());
    else if (a == "--stock-terrain") stockTerrain = next();
    else if (a == "--threads") threads = unsigned(std::atoi(next().c_str()));
    else if (a == "--plot") plotPath = next();
    else if (a == "--no-stock") noStock = true;
    else if (a == "--faces-per-region") gFacesPerRegion = size_t(std::atoll(next().c_str()));
    else if (a == "--pause") gPause = std::atof(next().c_str());
    else if (a == "--meshopt-huge-pages") meshopt_setAllocator(meshoptAllocate, meshoptDeallocate);
    else if (a == "--skip-terrain") skipTerrain = true;
    else if (a == "--skip-bunny") skipBunny = true;
    else if (a == "--skip-quad") skipQuad = true;
    else if (a == "--hard-quad") hardQuad = true;
    else if (a == "--hard-quad-irregular") hardQuad = hardIrregular = true;
    else if (a == "--quad-object") quadObject = true;
    else if (a == "--no-peers") noPeers = true;
    else if (a == "--quad-no-uv") quadNoUv = true;
    else if (a == "--where-max") whereMax = true;
    else if (a == "--bound") bounds = true;
    else if (a == "--quad-seed") quadSeed = std::strtoull(next().c_str(), nullptr, 10);
    else if (a == "--work-dir") workDir = next();
    else {
      std::fprintf(stderr, "usage: %s [--bunny PATH] [--terrain-quads N] [--runs K] [--terrain-samples S] "
                           "[--stock-terrain 0.1|all|none] [--threads T] [--plot PNG] [--skip-terrain] [--skip-bunny] "
                           "[--terrain-runs K] [--ratios 50,25,10,5,1] [--no-error] [--no-stock] "
                           "[--faces-per-region N] [--skip-quad] [--no-peers] [--work-dir DIR] [--quad-no-uv] [--quad-seed K] [--where-max] [--bound] [--hard-quad] [--hard-quad-irregular] [--quad-object] [--pause S] [--meshopt-huge-pages]\n", argv[0]);
      return 2;
    }
  }
  // The peers' files go there: a directory that is not there yet is made
  // (the peers' programs would each fail on a missing one).
  if (std::error_code ec; !std::filesystem::is_directory(workDir) && !std::filesystem::create_directories(workDir, ec)) {
    std::fprintf(stderr, "--work-dir %s: cannot create it: %s\n", workDir.c_str(), ec.message().c_str());
    return 2;
  }
  // MESHOPTIMIZER_VERSION is major*1000 + minor*10 (180 = 0.18).
  std::printf("# Decimation: ours vs meshopt_simplify %d.%d vs OpenMesh DecimaterT (machine: %s)\n",
              MESHOPTIMIZER_VERSION / 1000, (MESHOPTIMIZER_VERSION % 1000) / 10, hs::bench::threadsText().c_str());
  std::printf("load average at start: %s\n", hs::bench::loadAverageLine().c_str());

  struct Dataset {
    std::string name, shortName;
    MeshData mesh;
    double samples;
    int runs;
    bool stockAll, stockTen;
    bool peersAll = false, peersTen = false;  // Blender and MeshLab at every ratio / at 10%
  };
  std::vector<Dataset> sets;
  if (!skipBunny) {
    std::optional<MeshData> bunny = hs::bench::loadBunny(bunnyPath);
    if (!bunny) return 1;
    sets.push_back({"Stanford bunny", "Stanford bunny 69k", std::move(*bunny), 10.0, runs, true, true, false, true});
  }
  if (!skipQuad) {
    MeshData q = hs::bench::quadScan(180, 30.0, quadSeed);
    if (quadNoUv) {
      q.uvs.clear();
      weldExactDuplicates(q);
    }
    q.origin = glm::dvec3(431000.0, 5402000.0, 520.0);
    recenter(q);
    sets.push_back({"quad-dominant scan (32k quads triangulated, 2x2 UV atlas, 3 fins)", "quad scan 65k", std::move(q),
                    10.0, runs, false, true, true, false});
  }
  if (hardQuad) {
    MeshData q = hs::bench::hardQuadScan(180, 30.0, 23, hardIrregular);
    q.origin = glm::dvec3(431000.0, 5402000.0, 520.0);
    recenter(q);
    sets.push_back({std::string("hard quad scan (32k quads") + (hardIrregular ? ", irregular" : "") +
                        ", 2x2 UV atlas, thin walls, spikes, a narrow bridge, a fold, thin sheets, 3 fins)",
                    "hard quad scan", std::move(q), 10.0, runs, false, true, true, false});
  }
  if (quadObject) {
    MeshData q = hs::bench::quadObject();
    q.origin = glm::dvec3(431000.0, 5402000.0, 520.0);
    recenter(q);
    sets.push_back({"quad-dominant object (32k quads graded 12:1, irregular, 4 UV charts, horns, flakes, a ridge, 3 fins)",
                    "quad object", std::move(q), 10.0, runs, false, true, true, false});
  }
  if (!skipTerrain) {
    const auto t0 = Clock::now();
    MeshData t = hs::bench::scanTerrain(terrainQuads, 500.0);
    t.origin = glm::dvec3(656000.0, 5514000.0, 300.0);
    recenter(t);
    std::printf("generated the scan tile in %.1f s\n", seconds(t0, Clock::now()));
    const std::string k = std::to_string(t.triangleCount() / 1000) + "k";
    sets.push_back({"synthetic scan tile (" + k + " triangles, UV atlas 8x8, holes)", "scan tile " + k, std::move(t),
                    terrainSamples, terrainRuns, stockTerrain == "all", stockTerrain == "0.1" || stockTerrain == "all"});
  }

  using hs::bench::PlotMarker;
  std::vector<hs::bench::PlotPanel> panels;
  for (const Dataset& ds : sets) {
    ErrorOptions eo;
    eo.samplesPerFace = ds.samples;
    std::optional<ErrorMeter> meterStore;
    if (measureErrors) meterStore.emplace(ds.mesh, eo);
    const ErrorMeter* meter = meterStore ? &*meterStore : nullptr;
    printHeader(ds.name.c_str(), ds.mesh, ds.samples);
    // ErrorMeter::hausdorffUpperBound: no point of either surface is
    // further from the other than `upper` (the sampled maximum is a lower
    // bound), so rows can be told apart beyond the sampling's reach. Depth
    // 10, not the default 8: on the quad scan's fins 8 left the bound at
    // 2.66 mm for a result whose maximum is 1.96-2.02 mm.
    auto printBound = [&](const Row& r, const MeshData& out) {
      if (!bounds || !meter) return;
      const HausdorffBound b = meter->hausdorffUpperBound(out, r.error.hausdorff, 0.01, 10);
      std::printf("|  | (%s: Hausdorff certified within %.4e .. %.4e m, %llu pieces, %.2f s) | | | | | | | | | | | | | |\n",
                  r.method.c_str(), b.lower, b.upper, (unsigned long long)b.pieces, b.seconds);
    };
    hs::bench::PlotSeries sOurs{"ours (2 threads)", {200, 40, 40}, PlotMarker::Circle, false, {}, {}},
        sRefined{"ours + refine", {240, 120, 120}, PlotMarker::Circle, false, {}, {}},
        sMeshopt{"meshopt_simplify", {40, 90, 200}, PlotMarker::Square, false, {}, {}},
        sStock{"OpenMesh DecimaterT", {40, 150, 60}, PlotMarker::Triangle, false, {}, {}},
        sBlender{"Blender Decimate", {230, 140, 20}, PlotMarker::Square, false, {}, {}},
        sMeshlab{"MeshLab quadric", {140, 60, 170}, PlotMarker::Triangle, false, {}, {}};
    for (double ratio : ds.mesh.triangleCount() ? ratios : std::vector<double>{}) {
      MeshData oursOut, mo;
      Row ours, meshopt;
      runPair(ds.mesh, ratio, ds.runs, threads, ours, oursOut, meshopt, mo);
      if (measureErrors) {
        auto t0 = Clock::now();
        ours.error = meter->measure(oursOut);
        ours.errorTime = seconds(t0, Clock::now());
        t0 = Clock::now();
        meshopt.error = meter->measure(mo);
        meshopt.errorTime = seconds(t0, Clock::now());
        if (ours.error.constrainedVerticesMoved)
          std::printf("| | ours: %zu boundary/seam vertices off their polylines | | | | | | | | | | | | | |\n",
                      ours.error.constrainedVerticesMoved);
      }
      printRow(meshopt, ds.mesh, nullptr);
      printBound(meshopt, mo);
      printRow(ours, ds.mesh, &meshopt);
      printBound(ours, oursOut);
      if (measureErrors) {
        // The refinement, as an import runs it after the decimation.
        Row refined;
        refined.method = "ours + refine (" + std::to_string(threads) + " threads)";
        refined.ratio = ratio;
        refined.triangles = ours.triangles;
        MeshData out;
        RefineOptions ro;
        ro.threads = threads;
        std::vector<double> times;
        RefineReport rr;
        for (int k = 0; k < ds.runs; ++k) {
          out = oursOut;
          const auto t0 = Clock::now();
          rr = refineMaxError(*meter, out, ro);
          times.push_back(seconds(t0, Clock::now()));
        }
        std::sort(times.begin(), times.end());
        refined.time = ours.time + times[times.size() / 2];
        const auto t0 = Clock::now();
        refined.error = meter->measure(out);
        refined.errorTime = seconds(t0, Clock::now());
        printRow(refined, ds.mesh, &meshopt);
        printBound(refined, out);
        std::printf("|  | (refine: %.4f s, %zu of %zu vertices moved, %d rounds) | | | | | | | | | | | | | |\n",
                    times[times.size() / 2], rr.moved, rr.candidates, rr.iterations);
        sRefined.points.push_back({refined.time, refined.error.rel(refined.error.hausdorff)});
        char refinedLabel[16];
        std::snprintf(refinedLabel, sizeof refinedLabel, "%g%%", ratio * 100);
        sRefined.pointLabels.push_back(refinedLabel);
      }
      if (whereMax) {
        printWorst(ds.mesh, oursOut, "ours");
        printWorst(ds.mesh, mo, "meshopt");
      }
      char label[16];
      std::snprintf(label, sizeof label, "%g%%", ratio * 100);
      sOurs.points.push_back({ours.time, ours.error.rel(ours.error.hausdorff)});
      sOurs.pointLabels.push_back(label);
      sMeshopt.points.push_back({meshopt.time, meshopt.error.rel(meshopt.error.hausdorff)});
      sMeshopt.pointLabels.push_back(label);
      if (!noStock && (ds.stockAll || (ds.stockTen && ratio == 0.1))) {
        MeshData so;
        Row stock = runStock(ds.mesh, ours.triangles, ratio, so);
        if (measureErrors) {
          const auto t0 = Clock::now();
          stock.error = meter->measure(so);
          stock.errorTime = seconds(t0, Clock::now());
        }
        printRow(stock, ds.mesh, &meshopt);
        std::printf("|  | (OpenMesh: building its mesh with add_face took %.3f s more) | | | | | | | | | | | | | |\n",
                    stock.buildTime);
        sStock.points.push_back({stock.time, stock.error.rel(stock.error.hausdorff)});
        sStock.pointLabels.push_back(label);
      }
      if (!noPeers && (ds.peersAll || (ds.peersTen && ratio == 0.1))) {
        const hs::bench::PeerRun peers[2] = {hs::bench::runBlenderDecimate(ds.mesh, double(ours.triangles) / double(ds.mesh.triangleCount()), workDir),
                                             hs::bench::runMeshlabDecimate(ds.mesh, ours.triangles, workDir)};
        const char* names[2] = {"Blender 3.4 Decimate (collapse)", "MeshLab 2020.09 quadric edge collapse"};
        for (int k = 0; k < 2; ++k) {
          if (!peers[k].ran) {
            std::printf("|  | %s: %s | | | | | | | | | | | | | |\n", names[k], peers[k].note.c_str());
            continue;
          }
          Row pr;
          pr.method = names[k];
          pr.ratio = ratio;
          pr.triangles = peers[k].mesh.triangleCount();
          pr.time = peers[k].seconds;
          if (measureErrors) {
            const auto t0 = Clock::now();
            pr.error = meter->measure(peers[k].mesh);
            pr.errorTime = seconds(t0, Clock::now());
          }
          printRow(pr, ds.mesh, &meshopt);
          printBound(pr, peers[k].mesh);
          std::printf("|  | (%s: %s) | | | | | | | | | | | | | |\n", names[k], peers[k].note.c_str());
          (k == 0 ? sBlender : sMeshlab).points.push_back({pr.time, pr.error.rel(pr.error.hausdorff)});
          (k == 0 ? sBlender : sMeshlab).pointLabels.push_back(label);
        }
      }
    }
    panels.push_back({ds.shortName, "decimation time (s), targets labelled", "Hausdorff distance / bbox diagonal",
                      true, true, {sOurs, sMeshopt}});
    if (!sRefined.points.empty()) panels.back().series.push_back(sRefined);
    if (!sStock.points.empty()) panels.back().series.push_back(sStock);
    if (!sBlender.points.empty()) panels.back().series.push_back(sBlender);
    if (!sMeshlab.points.empty()) panels.back().series.push_back(sMeshlab);
  }

  if (!plotPath.empty() && !panels.empty()) {
    const std::string err = hs::bench::savePlotPng(panels, plotPath, 900, 640);
    if (err.empty())
      std::printf("\nerror-vs-time plot: %s\n", plotPath.c_str());
    else
      std::fprintf(stderr, "%s\n", err.c_str());
  }
  return 0;
}
