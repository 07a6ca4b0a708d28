// OBJ import at scale: our multi-threaded streaming reader against Assimp's
// OBJ reader on the same generated multi-million-triangle scan (UTM
// coordinates, texture coordinates, 8x8 atlas seams), each import in a
// child process of its own so its peak resident memory (VmHWM from
// /proc/self/status) is its own.
//
//   bench_obj_import [--quads 1580] [--file /tmp/hs_bench_scan.obj] [--keep]
//                    [--runs 1] [--skip-assimp]
//   bench_obj_import --child ours|assimp FILE     (one measurement, prints a line)
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "mesh/mesh_import.h"
#include "scan_terrain.h"

using namespace hs::mesh;

namespace {

int child(const std::string& reader, const std::string& path) {
  // What the process holds before reading (the libraries: Assimp and
  // OpenImageIO alone map about 120 MB), so the import's own peak can be
  // told apart.
  const size_t baseline = hs::bench::statusKiB("VmRSS:");
  ImportOptions o;
  o.up = UpAxis::Z;
  o.reader = reader == "assimp" ? Reader::Assimp : Reader::Obj;
  const auto t0 = std::chrono::steady_clock::now();
  const ImportResult r = importMesh(path, o);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!r.ok()) {
    std::printf("error %s\n", r.error.c_str());
    return 1;
  }
  // seconds triangles vertices meshBytes peakKiB baselineKiB hash
  std::printf("result %.6f %zu %zu %zu %zu %zu %016llx\n", s, r.mesh->triangleCount(), r.mesh->vertexCount(),
              r.mesh->memoryBytes(), hs::bench::statusKiB("VmHWM:"), baseline, (unsigned long long)contentHash(*r.mesh));
  return 0;
}

struct Measurement {
  double seconds = 0;
  size_t triangles = 0, vertices = 0, meshBytes = 0, peakKiB = 0, baselineKiB = 0;
  std::string hash, error;
};

Measurement measure(const char* self, const std::string& reader, const std::string& path) {
  Measurement m;
  int fd[2];
  if (pipe(fd) != 0) return m;
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fd[1], 1);
    close(fd[0]);
    execl(self, self, "--child", reader.c_str(), path.c_str(), nullptr);
    _exit(127);
  }
  close(fd[1]);
  std::string out;
  char buf[512];
  ssize_t n;
  while ((n = read(fd[0], buf, sizeof buf)) > 0) out.append(buf, size_t(n));
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  char hash[32] = {0};
  if (std::sscanf(out.c_str(), "result %lf %zu %zu %zu %zu %zu %31s", &m.seconds, &m.triangles, &m.vertices,
                  &m.meshBytes, &m.peakKiB, &m.baselineKiB, hash) == 7)
    m.hash = hash;
  else
    m.error = out.empty() ? "child failed" : out;
  return m;
}

// A photogrammetry-style OBJ: UTM coordinates with millimetres, v/vt faces.
void writeScanObj(const std::string& path, int quads) {
  MeshData m = hs::bench::scanTerrain(quads, 500.0);
  const glm::dvec3 origin(656000.0, 5514000.0, 300.0);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  std::vector<char> buffer(1 << 20);
  std::setvbuf(f, buffer.data(), _IOFBF, buffer.size());
  std::fprintf(f, "# synthetic scan tile, %zu triangles\nmtllib scan.mtl\nusemtl atlas\n", m.triangleCount());
  for (const auto& p : m.positions) {
    const glm::dvec3 w = origin + glm::dvec3(p);
    std::fprintf(f, "v %.3f %.3f %.3f\n", w.x, w.y, w.z);
  }
  for (const auto& t : m.uvs) std::fprintf(f, "vt %.6f %.6f\n", double(t.x), 1.0 - double(t.y));
  for (size_t i = 0; i < m.indices.size(); i += 3)
    std::fprintf(f, "f %u/%u %u/%u %u/%u\n", m.indices[i] + 1, m.indices[i] + 1, m.indices[i + 1] + 1,
                 m.indices[i + 1] + 1, m.indices[i + 2] + 1, m.indices[i + 2] + 1);
  std::fclose(f);
  std::ofstream mtl(std::filesystem::path(path).parent_path() / "scan.mtl");
  mtl << "newmtl atlas\nKd 1 1 1\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 4 && std::string(argv[1]) == "--child") return child(argv[2], argv[3]);
  int quads = 1580, runs = 1;
  std::string path = "/tmp/hs_bench_scan.obj";
  bool keep = false, skipAssimp = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quads" && i + 1 < argc) quads = std::atoi(argv[++i]);
    else if (a == "--file" && i + 1 < argc) path = argv[++i];
    else if (a == "--runs" && i + 1 < argc) runs = std::max(1, std::atoi(argv[++i]));
    else if (a == "--keep") keep = true;
    else if (a == "--skip-assimp") skipAssimp = true;
    else {
      std::fprintf(stderr, "usage: %s [--quads N] [--file PATH] [--runs K] [--keep] [--skip-assimp]\n", argv[0]);
      return 2;
    }
  }
  if (!std::filesystem::exists(path)) {
    const auto t0 = std::chrono::steady_clock::now();
    writeScanObj(path, quads);
    std::printf("wrote %s in %.1f s\n", path.c_str(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  const double mb = double(std::filesystem::file_size(path)) / 1e6;
  std::printf("# OBJ import: %s, %.1f MB (load average at start: %s)\n\n", path.c_str(), mb,
              hs::bench::loadAverageLine().c_str());
  std::printf("| reader | seconds | MB/s | Mtriangles/s | triangles | vertices | mesh MB | peak RSS MB | RSS before MB | (peak - before) / mesh | peak / mesh | speed vs Assimp |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  Measurement best[2];
  const char* names[2] = {"ours (obj, all threads)", "Assimp 5.2 (OBJ)"};
  for (int which = 0; which < (skipAssimp ? 1 : 2); ++which)
    for (int r = 0; r < runs; ++r) {
      const Measurement m = measure(argv[0], which == 0 ? "ours" : "assimp", path);
      if (!m.error.empty()) {
        std::printf("| %s | failed: %s |\n", names[which], m.error.c_str());
        break;
      }
      if (best[which].seconds == 0 || m.seconds < best[which].seconds) best[which] = m;
    }
  for (int which = 0; which < 2; ++which) {
    const Measurement& m = best[which];
    if (m.seconds == 0) continue;
    char vs[32] = "";
    if (best[1].seconds > 0) std::snprintf(vs, sizeof vs, "%.2fx faster", best[1].seconds / m.seconds);
    std::printf("| %s | %.3f | %.1f | %.2f | %zu | %zu | %.1f | %.1f | %.1f | %.2f | %.2f | %s |\n", names[which],
                m.seconds, mb / m.seconds, double(m.triangles) / m.seconds / 1e6, m.triangles, m.vertices,
                double(m.meshBytes) / 1e6, double(m.peakKiB) * 1024.0 / 1e6, double(m.baselineKiB) * 1024.0 / 1e6,
                double(m.peakKiB - m.baselineKiB) * 1024.0 / double(m.meshBytes),
                double(m.peakKiB) * 1024.0 / double(m.meshBytes), which ? "1.00x" : vs);
  }
  if (best[0].seconds > 0 && best[1].seconds > 0)
    std::printf("\nsame mesh from both readers: %s (vertex and triangle counts), content hash %s\n",
                best[0].triangles == best[1].triangles && best[0].vertices == best[1].vertices ? "yes" : "NO",
                best[0].hash == best[1].hash ? "identical" : "differs (vertex order / float rounding of Assimp's single-precision parse)");
  if (!keep) std::filesystem::remove(path);
  return 0;
}
