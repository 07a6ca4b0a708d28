// The cases of meshproc_defect_campaign (defect_campaign.cpp): one seeded
// sequence per seed, so that a test can replay a case the campaign found.
// A trial's mesh depends on the draws of every trial before it, so a case
// is reached by generating those before it (about a millisecond each).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "mesh/mesh_export.h"
#include "mesh/mesh_import.h"
#include "meshproc/error_metrics.h"
#include "meshproc/mesh_process.h"
#include "mesh_builders.h"

namespace hs::test {

struct DefectCase {
  hs::mesh::MeshData in;
  hs::mesh::ProcessOptions options;
  int trial = 0;
  int target = 0;     // 0, 1, 2: a ratio of 2%, 10%, 50%; 3: a maximum error
  double scale = 1;   // the grid's 10 m times this
  std::string where;  // "seed S trial T: ..." with what the case is made of
};

class DefectCases {
 public:
  explicit DefectCases(unsigned seed) : seed_(seed), rng_(seed) {}

  // The next trial's case. `without` leaves its defect of that index out,
  // with the same draws, so that the later defects stay where they were.
  DefectCase next(int without = -1) {
    using namespace hs::mesh;
    DefectCase c;
    c.trial = trial_++;
    const int n = 10 + int(rng_() % 41);
    const bool seam = rng_() % 2 == 0;
    MeshData grid = curvedGrid(n, 10.0, 0.3 * double(rng_() % 3), seam);
    const bool utm = rng_() % 4 == 0;
    if (utm) grid.origin = glm::dvec3(656059.0, 5514553.0, 1713.0);
    if (rng_() % 3 == 0) {
      // Two materials, split down the middle (a material border is a seam).
      std::vector<uint32_t> left, right;
      for (size_t f = 0; f < grid.triangleCount(); ++f) {
        const float cx = (grid.positions[grid.indices[f * 3]].x + grid.positions[grid.indices[f * 3 + 1]].x +
                          grid.positions[grid.indices[f * 3 + 2]].x) / 3.0f;
        auto& side = cx < 5.0f ? left : right;
        side.insert(side.end(), grid.indices.begin() + f * 3, grid.indices.begin() + f * 3 + 3);
      }
      grid.indices = left;
      grid.indices.insert(grid.indices.end(), right.begin(), right.end());
      grid.materials.resize(2);
      grid.submeshes = {{0, uint32_t(left.size()), 0}, {uint32_t(left.size()), uint32_t(right.size()), 1}};
    }
    c.in = grid;
    const int defects = int(rng_() % 15);
    std::string kinds;
    for (int d = 0; d < defects; ++d) {
      const int kind = int(rng_() % 11);
      kinds += (kinds.empty() ? "" : ",") + std::to_string(kind);
      if (d == without) {
        MeshData scratch = grid;
        addDefect(scratch, grid, kind, rng_);
      } else {
        addDefect(c.in, grid, kind, rng_);
      }
    }
    // A 1 cm object, the 10 m patch, or 10 km of terrain: the same shape.
    const double scales[] = {1e-3, 1.0, 1e3};
    c.scale = scales[rng_() % 3];
    for (auto& p : c.in.positions) p *= float(c.scale);
    ProcessOptions& o = c.options;
    o.decimate = true;
    c.target = int(rng_() % 4);
    const double ratios[] = {0.02, 0.1, 0.5};
    if (c.target < 3) {
      o.decimation.targetRatio = ratios[c.target];
    } else {
      o.decimation.targetRatio = 0;
      o.decimation.maxError = 0.05 * c.scale;
    }
    o.decimation.lockBoundaries = rng_() % 5 == 0;
    o.decimation.facesPerRegion = 1000;
    o.lodLevels = int(rng_() % 3);
    o.error.samplesPerFace = 2;
    char where[256];
    const std::string targetText =
        c.target < 3 ? std::to_string(int(ratios[c.target] * 100)) + "%" : "max error 0.05 m x scale";
    std::snprintf(where, sizeof where, "seed %u trial %d: %dx%d grid x %g%s%s%s, defects [%s], %s%s", seed_, c.trial, n,
                  n, c.scale, seam ? ", seam" : "", grid.submeshes.size() > 1 ? ", 2 materials" : "",
                  utm ? ", UTM" : "", kinds.c_str(), targetText.c_str(),
                  o.decimation.lockBoundaries ? ", borders locked" : "");
    c.where = where;
    return c;
  }

 private:
  unsigned seed_;
  std::mt19937 rng_;
  int trial_ = 0;
};

// Trial `trial` of seed `seed`, as the campaign makes it.
inline DefectCase defectCase(unsigned seed, int trial, int without = -1) {
  DefectCases cases(seed);
  for (int t = 0; t < trial; ++t) cases.next();
  return cases.next(without);
}

// Exports `m` as OBJ and GLB (relative, with the offset sidecar) and binary
// PLY (world: doubles, Z up), reads each back with --origin auto
// (our OBJ and PLY readers, Assimp for GLB) and compares every triangle's
// corners, at their world places, and UVs, to float precision of the
// mesh's extent. Returns what differed, per format.
inline std::vector<std::string> checkExportRoundTrip(const hs::mesh::MeshData& m, const std::string& stem) {
  using namespace hs::mesh;
  std::vector<std::string> failures;
  const Bounds b = m.bounds();
  const double extent = b.empty ? 1.0 : glm::length(glm::dvec3(b.max) - glm::dvec3(b.min)) +
                                            glm::length(glm::dvec3(b.max)) + glm::length(glm::dvec3(b.min));
  struct Way {
    ExportFormat format;
    const char* ext;
    bool world;
    double tolerance;  // metres
  };
  // The file's doubles (world PLY) are exact; MeshData holds them as floats
  // about a double origin again, so every way comes back to float precision.
  const Way ways[] = {{ExportFormat::Obj, ".obj", false, 4e-7 * extent},
                      {ExportFormat::Ply, ".ply", true, 4e-7 * extent},
                      {ExportFormat::Glb, ".glb", false, 4e-7 * extent}};
  for (const Way& w : ways) {
    ExportOptions eo;
    eo.format = w.format;
    eo.world = w.world;
    eo.zUp = true;
    const std::string path = stem + w.ext;
    const ExportResult er = exportMesh(m, path, eo);
    if (!er.ok()) {
      failures.push_back(std::string(w.ext) + ": export failed: " + er.error);
      continue;
    }
    ImportOptions io;
    io.up = w.format == ExportFormat::Glb ? UpAxis::Auto : UpAxis::Z;
    // Relative files have their origin in the sidecar, which --origin
    // auto reads; the one file name is reused from case to case, so a
    // sidecar left by an earlier case must not move this one.
    io.geoOffsetMode = ImportOptions::GeoOffsetMode::Auto;
    io.recenter = false;
    const ImportResult back = importMesh(path, io);
    if (!back.ok()) {
      failures.push_back(std::string(w.ext) + ": import failed: " + back.error);
      continue;
    }
    const MeshData& g = *back.mesh;
    if (g.triangleCount() != m.triangleCount()) {
      failures.push_back(std::string(w.ext) + ": " + std::to_string(g.triangleCount()) + " triangles back of " +
                         std::to_string(m.triangleCount()));
      continue;
    }
    double worst = 0;
    float worstUv = 0;
    const bool uvs = !m.uvs.empty() && m.uvs.size() == m.positions.size();
    for (size_t c = 0; c < m.indices.size(); ++c) {
      const glm::dvec3 want = m.origin + glm::dvec3(m.positions[m.indices[c]]);
      const glm::dvec3 got = g.origin + glm::dvec3(g.positions[g.indices[c]]);
      worst = std::max(worst, glm::length(want - got));
      if (uvs && g.uvs.size() == g.positions.size())
        worstUv = std::max(worstUv, glm::length(m.uvs[m.indices[c]] - g.uvs[g.indices[c]]));
    }
    // Materials: faces that share one share one when read back, and faces
    // of different ones stay apart (names may be made up on the way).
    // (pairs is sorted, so the distinct first members are runs.)
    const std::vector<int> mm = faceMaterials(m), gm = faceMaterials(g);
    std::vector<std::pair<int, int>> pairs;
    for (size_t f = 0; f < mm.size(); ++f) pairs.emplace_back(mm[f], gm[f]);
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    bool oneToOne = true;
    for (size_t i = 0; i < pairs.size(); ++i)
      for (size_t j = i + 1; j < pairs.size(); ++j)
        oneToOne &= (pairs[i].first == pairs[j].first) == (pairs[i].second == pairs[j].second);
    // PLY holds no materials, and must say so when there were several.
    size_t used = 0;
    for (size_t i = 0; i < pairs.size(); ++i) used += i == 0 || pairs[i].first != pairs[i - 1].first;
    if (w.format == ExportFormat::Ply) {
      if (used > 1 && er.warnings.empty()) failures.push_back(std::string(w.ext) + ": materials dropped unsaid");
    } else if (!oneToOne) {
      failures.push_back(std::string(w.ext) + ": faces changed material");
    }
    if (!(worst <= w.tolerance))
      failures.push_back(std::string(w.ext) + ": a corner came back " + std::to_string(worst) + " m off (tolerance " +
                         std::to_string(w.tolerance) + " m)");
    if (uvs && g.uvs.size() != g.positions.size()) failures.push_back(std::string(w.ext) + ": UVs lost");
    if (!(worstUv <= 1e-6f))
      failures.push_back(std::string(w.ext) + ": a UV came back " + std::to_string(worstUv) + " off");
  }
  return failures;
}

// What processing a case gave, by the campaign's checks.
struct DefectOutcome {
  std::vector<std::string> failures;  // empty: the case passed
  int runs = 0;                       // decimation runs (one thread)
  double kept = 0;                    // triangles out / triangles in (one thread)
};

// Processes the case on one thread and on two. Every result must be valid
// (indices in range, no face repeating a vertex, finite positions, LOD
// levels' indices in range), the same on both thread counts, with no
// boundary or seam vertex off the input's polylines, a Hausdorff below 5%
// of the diagonal (2% targets aside: a handful of triangles cannot follow
// a small grid), and a maximum error met as measured.
inline DefectOutcome checkDefectCase(const DefectCase& c, const std::string& exportStem = {}) {
  using namespace hs::mesh;
  DefectOutcome result;
  auto fail = [&](const std::string& what) { result.failures.push_back(what); };
  ProcessOptions o = c.options;
  uint64_t hashes[2] = {0, 0};
  for (unsigned threads : {1u, 2u}) {
    o.decimation.threads = o.error.threads = o.cleaning.threads = threads;
    const ProcessResult r = processMesh(c.in, o);
    if (!r.ok()) {
      fail("refused: " + r.error);
      return result;
    }
    const MeshData& out = r.mesh;
    for (size_t t = 0; t < out.triangleCount(); ++t) {
      const uint32_t i = out.indices[t * 3], j = out.indices[t * 3 + 1], l = out.indices[t * 3 + 2];
      if (i >= out.vertexCount() || j >= out.vertexCount() || l >= out.vertexCount() || i == j || j == l || i == l) {
        fail("face " + std::to_string(t) + " is invalid");
        break;
      }
    }
    for (const auto& p : out.positions)
      if (!std::isfinite(p.x + p.y + p.z)) {
        fail("a position is not finite");
        break;
      }
    for (const MeshData& level : r.lods)
      for (uint32_t i : level.indices)
        if (i >= level.vertexCount()) {
          fail("a LOD level's index is out of range");
          break;
        }
    const ErrorReport& e = r.report.error;
    if (threads == 1 && !exportStem.empty())
      for (const std::string& f : checkExportRoundTrip(out, exportStem)) fail("export " + f);
    if (threads == 1) {
      result.runs = r.report.maxErrorPasses;
      result.kept = double(out.triangleCount()) / double(c.in.triangleCount());
      if (e.constrainedVerticesMoved)
        fail(std::to_string(e.constrainedVerticesMoved) + " boundary/seam vertices off the input's, by up to " +
             std::to_string(e.constrainedMaxDeviation) + " m");
      if (c.target != 0 && !(e.rel(e.hausdorff) < 0.05))
        fail("Hausdorff " + std::to_string(e.rel(e.hausdorff)) + " of the diagonal");
      if (c.target == 3 && !(e.hausdorff <= o.decimation.maxError))
        fail("maximum error not met: " +
             std::to_string(int(std::round(100.0 * (e.hausdorff / o.decimation.maxError - 1.0)))) + "% over after " +
             std::to_string(r.report.maxErrorPasses) + " runs");
    }
    hashes[threads - 1] = contentHash(out);
  }
  if (result.failures.empty() && hashes[0] != hashes[1]) fail("differs between 1 and 2 threads");
  return result;
}

}  // namespace hs::test
