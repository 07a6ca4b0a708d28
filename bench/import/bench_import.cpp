// bench_import: mesh import throughput of our streaming OBJ and PLY readers
// against Assimp's readers of the same files (the peer the foundation and
// mesh part-2 issues name), on the Stanford bunny and on a synthetic
// scan-like mesh (a noisy terrain grid with texture coordinates at UTM
// offsets, about 2M triangles by default) written as OBJ and as binary PLY
// (double coordinates, as Metashape and OpenDroneMap write UTM). Best of N
// runs, each in a process of its own (this program run with --child) so
// its peak memory is its own; next to the speed, the largest position error
// against the coordinates the file holds (Assimp reads floats; at UTM
// northings they are 0.5 m apart).
//
//   bench_import [--grid N] [--runs R] [--dir FOLDER]
//
// --grid N  the synthetic grid has N x N quads (2 N^2 triangles; default 1000)
// --runs R  imports per reader and file, best taken (default 3)
// --dir F   where to write the synthetic OBJ (default: the system temp folder)
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "bench/common/bench_util.h"
#include "mesh/mesh_import.h"

namespace fs = std::filesystem;
using namespace hs::mesh;

namespace {

// The synthetic scan: (n+1)^2 vertices 0.5 m apart at UTM-like coordinates
// (easting 500 km, northing 4400 km), each point moved up to 15 cm off the
// grid, heights of a few metres of rolling terrain plus millimetre noise, one
// vt per vertex, two triangles per quad, all written to the millimetre.
// Returns the coordinates exactly as written (parsed back from the text).
std::vector<glm::dvec3> writeScanObj(const std::string& path, int n) {
  std::vector<glm::dvec3> written;
  written.reserve(size_t(n + 1) * size_t(n + 1));
  std::ofstream out(path, std::ios::binary);
  std::mt19937 rng(12345);
  std::normal_distribution<double> noise(0.0, 0.004);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);  // scan points do not sit on a grid
  std::string buf;
  buf.reserve(1 << 20);
  char line[160];
  out << "# synthetic scan written by bench_import: " << n << " x " << n << " quads, UTM coordinates, Z up\n";
  for (int y = 0; y <= n; ++y) {
    for (int x = 0; x <= n; ++x) {
      const double e = 500000.0 + 0.5 * x + jitter(rng), no = 4400000.0 + 0.5 * y + jitter(rng);
      const double h = 250.0 + 6.0 * std::sin(x * 0.013) * std::cos(y * 0.011) + 2.0 * std::sin((x + y) * 0.05) + noise(rng);
      const int len = std::snprintf(line, sizeof line, "v %.3f %.3f %.3f\n", e, no, h);
      buf.append(line, size_t(len));
      // What the file says, to double precision.
      double v[3];
      char* p = line + 2;
      for (double& c : v) c = std::strtod(p, &p);
      written.emplace_back(v[0], v[1], v[2]);
    }
    if (buf.size() > (1u << 20) - 4096) {
      out << buf;
      buf.clear();
    }
  }
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      const int len = std::snprintf(line, sizeof line, "vt %.6f %.6f\n", double(x) / n, double(y) / n);
      buf.append(line, size_t(len));
      if (buf.size() > (1u << 20) - 4096) {
        out << buf;
        buf.clear();
      }
    }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x + 1, b = a + 1, c = a + n + 2, d = a + n + 1;
      const int len = std::snprintf(line, sizeof line, "f %d/%d %d/%d %d/%d\nf %d/%d %d/%d %d/%d\n", a, a, b, b, c, c, a, a,
                                    c, c, d, d);
      buf.append(line, size_t(len));
      if (buf.size() > (1u << 20) - 4096) {
        out << buf;
        buf.clear();
      }
    }
  out << buf;
  return written;
}

// The same scan as binary little-endian PLY: the coordinates written (as
// doubles, exactly), s t as floats, the same triangles.
void writeScanPly(const std::string& path, const std::vector<glm::dvec3>& written, int n) {
  std::ofstream out(path, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\ncomment synthetic scan written by bench_import\nelement vertex "
      << written.size()
      << "\nproperty double x\nproperty double y\nproperty double z\nproperty float s\nproperty float t\n"
         "element face "
      << size_t(2) * size_t(n) * size_t(n) << "\nproperty list uchar int vertex_indices\nend_header\n";
  std::string buf;
  for (size_t i = 0; i < written.size(); ++i) {
    const double xyz[3] = {written[i].x, written[i].y, written[i].z};
    const float st[2] = {float(int(i) % (n + 1)) / float(n), float(int(i) / (n + 1)) / float(n)};
    buf.append(reinterpret_cast<const char*>(xyz), 24);
    buf.append(reinterpret_cast<const char*>(st), 8);
  }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int32_t a = y * (n + 1) + x, b = a + 1, c = a + n + 2, d = a + n + 1;
      const int32_t t1[3] = {a, b, c}, t2[3] = {a, c, d};
      for (const int32_t* t : {t1, t2}) {
        buf.push_back(char(3));
        buf.append(reinterpret_cast<const char*>(t), 12);
      }
    }
  out << buf;
}

// Largest distance from a written coordinate to the nearest imported vertex
// (uniform grid; distances beyond one cell count as the cell size).
double maxPositionError(const std::vector<glm::dvec3>& written, const MeshData& m, double cell) {
  auto key = [&](const glm::dvec3& p) {
    const glm::dvec3 c = glm::floor(p / cell);
    return (uint64_t(int64_t(c.x) & 0x1fffff) << 42) | (uint64_t(int64_t(c.y) & 0x1fffff) << 21) |
           uint64_t(int64_t(c.z) & 0x1fffff);
  };
  std::unordered_map<uint64_t, std::vector<glm::dvec3>> grid;
  grid.reserve(m.positions.size());
  for (const auto& p : m.positions) {
    const glm::dvec3 w = m.origin + glm::dvec3(p);
    grid[key(w)].push_back(w);
  }
  double worst = 0.0;
  for (const auto& p : written) {
    double best = cell;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = grid.find(key(p + glm::dvec3(dx, dy, dz) * cell));
          if (it == grid.end()) continue;
          for (const auto& q : it->second) best = std::min(best, glm::length(q - p));
        }
    worst = std::max(worst, best);
  }
  return worst;
}

struct Row {
  std::string file, reader;
  double megabytes = 0, seconds = 0;
  size_t triangles = 0;
  double error = 0;
  double peakMb = 0;  // the child process's peak resident set
  std::string failure;
};

std::string gSelf;  // this program, for --child runs

// One import in a process of its own: "seconds triangles peak_kB" or an error.
bool childImport(const std::string& file, Reader reader, UpAxis up, double& seconds, size_t& triangles,
                 double& peakMb, std::string& error) {
  const std::string cmd = gSelf + " --child '" + file + "' " + std::to_string(int(reader)) + " " +
                          std::to_string(int(up)) + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) {
    error = "cannot start " + gSelf;
    return false;
  }
  char line[4096] = "";
  const bool got = std::fgets(line, sizeof line, p) != nullptr;
  const int status = pclose(p);
  double kb = 0;
  if (!got || status != 0 || std::sscanf(line, "%lf %zu %lf", &seconds, &triangles, &kb) != 3) {
    error = got ? line : "the child printed nothing";
    return false;
  }
  peakMb = kb / 1024.0;
  return true;
}

int runChild(const std::string& file, int reader, int up) {
  ImportOptions o;
  o.reader = Reader(reader);
  o.up = UpAxis(up);
  const auto t0 = std::chrono::steady_clock::now();
  const ImportResult res = importMesh(file, o);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!res.ok()) {
    std::printf("%s\n", res.error.c_str());
    return 1;
  }
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  std::printf("%.6f %zu %ld\n", s, res.mesh->triangleCount(), long(ru.ru_maxrss));
  return 0;
}

Row measure(const std::string& file, const std::string& label, Reader reader, UpAxis up, int runs,
            const std::vector<glm::dvec3>* written) {
  Row row;
  row.file = label;
  const bool ply = fs::path(file).extension() == ".ply";
  row.reader = reader == Reader::Assimp ? "Assimp" : ply ? "own PLY" : "own OBJ";
  row.megabytes = double(fs::file_size(file)) / 1e6;
  row.seconds = INFINITY;
  ImportOptions o;
  o.reader = reader;
  o.up = up;
  // The position error from one import here; times and memory from
  // imports in processes of their own.
  if (written) {
    ImportResult res = importMesh(file, o);
    if (!res.ok()) {
      row.failure = res.error;
      return row;
    }
    row.error = maxPositionError(*written, *res.mesh, 1.0);
  }
  for (int r = 0; r < runs; ++r) {
    double s = 0, peak = 0;
    if (!childImport(file, reader, up, s, row.triangles, peak, row.failure)) return row;
    row.seconds = std::min(row.seconds, s);
    row.peakMb = std::max(row.peakMb, peak);
  }
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  gSelf = fs::canonical("/proc/self/exe").string();
  if (argc == 5 && std::strcmp(argv[1], "--child") == 0) return runChild(argv[2], std::atoi(argv[3]), std::atoi(argv[4]));
  int grid = 1000, runs = 3;
  std::string dir = fs::temp_directory_path().string();
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--grid" && i + 1 < argc) grid = std::atoi(argv[++i]);
    else if (a == "--runs" && i + 1 < argc) runs = std::atoi(argv[++i]);
    else if (a == "--dir" && i + 1 < argc) dir = argv[++i];
    else {
      std::fprintf(stderr, "usage: bench_import [--grid N] [--runs R] [--dir FOLDER]\n");
      return 2;
    }
  }
  if (grid < 1 || runs < 1) {
    std::fprintf(stderr, "bench_import: --grid and --runs need positive numbers\n");
    return 2;
  }

  const std::string bunny = HS_SOURCE_DIR "/resources/demo/stanford-bunny.obj";
  const std::string scan = (fs::path(dir) / ("bench_import_scan_" + std::to_string(grid) + ".obj")).string();
  std::printf("writing %s (%d x %d quads) ...\n", scan.c_str(), grid, grid);
  std::fflush(stdout);
  const std::vector<glm::dvec3> written = writeScanObj(scan, grid);
  const std::string scanPly = fs::path(scan).replace_extension(".ply").string();
  writeScanPly(scanPly, written, grid);

  std::vector<Row> rows;
  for (Reader r : {Reader::Obj, Reader::Assimp}) rows.push_back(measure(bunny, "stanford-bunny.obj", r, UpAxis::Y, runs, nullptr));
  for (Reader r : {Reader::Obj, Reader::Assimp}) rows.push_back(measure(scan, fs::path(scan).filename().string(), r, UpAxis::Z, runs, &written));
  for (Reader r : {Reader::Auto, Reader::Assimp})
    rows.push_back(measure(scanPly, fs::path(scanPly).filename().string(), r, UpAxis::Z, runs, &written));
  std::error_code ec;
  fs::remove(scan, ec);
  fs::remove(scanPly, ec);

  const double load = hs::bench::loadAverage();
  std::printf("\nOBJ and PLY import, best of %d (Release build; %s; load average %.2f)\n\n", runs,
              hs::bench::threadsText().c_str(), load);
  std::printf("| file | MB | triangles | reader | best s | MB/s | M triangles/s | own / Assimp | peak MB | max position error |\n");
  std::printf("| --- | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  for (size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    if (!r.failure.empty()) {
      std::printf("| %s | %.1f | | %s | failed: %s | | | | | |\n", r.file.c_str(), r.megabytes, r.reader.c_str(), r.failure.c_str());
      continue;
    }
    std::string ratio;
    if (i % 2 == 1 && rows[i - 1].failure.empty()) {
      char b[32];
      std::snprintf(b, sizeof b, "%.2fx", r.seconds / rows[i - 1].seconds);
      ratio = b;
    }
    char err[32] = "";
    if (i >= 2) std::snprintf(err, sizeof err, "%.3g m", r.error);
    std::printf("| %s | %.1f | %zu | %s | %.3f | %.1f | %.2f | %s | %.0f | %s |\n", r.file.c_str(), r.megabytes, r.triangles,
                r.reader.c_str(), r.seconds, r.megabytes / r.seconds, double(r.triangles) / r.seconds / 1e6, ratio.c_str(),
                r.peakMb, err);
  }
  std::printf("\nown / Assimp: how many times faster the own reader is (Assimp's time over ours).\n"
              "max position error: largest distance from a coordinate in the file to the nearest imported vertex\n"
              "(a lower bound where a vertex moved next to another one).\n"
              "peak MB: the importing process's peak resident set (each import runs in a process of its own).\n");
  return 0;
}
