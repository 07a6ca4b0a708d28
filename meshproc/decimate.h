#pragma once
// Mesh decimation: quadric error metric with optimal vertex placement on an
// OpenMesh half-edge mesh, engineered for multi-million-triangle scans (see
// docs/meshes.md for the algorithm and its guarantees).
//
// What it keeps:
//   * open boundaries and UV seams (and edges between materials): their
//     vertices only ever merge along the polyline into a neighbour on the
//     same polyline and never move, so every remaining seam/boundary vertex
//     is an original vertex of its polyline and the texture stays in place;
//     where polylines meet or end the vertex is fixed;
//   * locked vertices (tile borders of multi-tile scans) do not move or go;
//   * no collapse flips a triangle or turns its normal by more than
//     maxNormalDeviationDeg, and none creates a sliver worse than
//     minTriangleQuality unless a triangle there was already worse.
// Output is deterministic: it depends on the input and options only, not on
// the thread count or timing (partitions are fixed by facesPerRegion).
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "core/params.h"
#include "core/progress.h"
#include "mesh/mesh_data.h"
#include "mesh/nonmanifold_split.h"

namespace hs::mesh {

struct DecimateOptions {
  // Targets. Decimation stops at the first of: the triangle target reached,
  // or no collapse left whose estimated error is within maxError.
  // targetTriangles (if > 0) wins over targetRatio; ratio 0 with a finite
  // maxError means "as far as the error allows".
  double targetRatio = 0.5;
  size_t targetTriangles = 0;
  double maxError = std::numeric_limits<double>::infinity();  // metres

  // Lock every open-boundary vertex (tile borders: adjacent tiles decimated
  // separately still meet exactly).
  bool lockBoundaries = false;
  // Optional, one per input vertex: nonzero locks that vertex.
  std::vector<uint8_t> lockedVertices;

  double maxNormalDeviationDeg = 60.0;  // per collapse, against the face before it
  double minTriangleQuality = 0.1;      // 4*sqrt(3)*area / sum of squared edges (1 = equilateral)

  // Copy the input's textures into the result. LOD chains turn this off:
  // their levels keep the material indices and share the base's images.
  bool copyTextures = true;

  unsigned threads = 0;            // 0 = every available thread (core/parallel.h)
  size_t facesPerRegion = 25000;   // partition size (at most 64 regions); fixes the output, whatever the thread count
};

struct DecimateReport {
  size_t trianglesIn = 0, verticesIn = 0;
  size_t trianglesOut = 0, verticesOut = 0;
  size_t targetTriangles = 0;
  bool targetReached = false;
  size_t collapses = 0;
  size_t rejectedTopology = 0;  // link condition, would close a hole or pinch
  size_t rejectedFlip = 0;      // would flip or turn a face too far
  size_t rejectedSliver = 0;    // would create a needle/sliver triangle
  size_t boundaryVertices = 0, seamVertices = 0, fixedVertices = 0, lockedVertices = 0;
  size_t degenerateFacesRemoved = 0;  // faces with two corners at one point (input not cleaned)
  NonManifoldSplitStats nonManifold;  // split at welded-position level before building
  double maxEstimatedError = 0.0;     // metres, largest quadric error accepted
  unsigned regions = 0, threads = 0;
  unsigned rounds = 0;                // parallel rounds (shared error thresholds), all levels
  unsigned levels = 0;                // levels of merged regions that ran rounds (region_levels.h)
  size_t lastRegionCollapses = 0;     // of `collapses`, those of the last, single region (serial)
  // secondsRegions: the levels of two or more regions (parallel);
  // secondsLastRegion: the last level, one region finishing the count.
  double secondsSetup = 0, secondsRegions = 0, secondsLastRegion = 0, secondsOutput = 0, secondsTotal = 0;
};

struct DecimateResult {
  MeshData mesh;
  DecimateReport report;
  bool cancelled = false;
  std::string error;  // set when the input could not be decimated
  bool ok() const { return error.empty() && !cancelled; }
};

// Decimates `input` (triangles, optional UVs, submeshes/materials kept;
// textures are shared, normals are recomputed). Never throws except
// std::bad_alloc.
DecimateResult decimate(const MeshData& input, const DecimateOptions& options,
                        const Progress* progress = nullptr);

// The decimation targets a user sets, declared once: target_ratio_pct (a
// share of the triangles, 0.01..100%) and target_triangles (4 .. 2^31-1:
// fewer than a tetrahedron is no mesh). The Import dialog's fields and
// parseDecimateTarget check against these.
const std::vector<ParamDecl>& decimateTargetDecls();

// Parses "500k", "2.5M", "120000" (a triangle count) or "10%" (a ratio) into
// `options` (the CLI's --decimate-to), within decimateTargetDecls()'
// ranges. False with `error` on bad text.
bool parseDecimateTarget(std::string_view text, DecimateOptions& options, std::string& error);

}  // namespace hs::mesh
