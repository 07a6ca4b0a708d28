#pragma once
// The one call the import dialog and `hybridscape-cli import` make after
// reading a mesh: clean it, optionally decimate it (to a ratio, a triangle
// count or a maximum error in metres), measure what the decimation cost,
// and build LODs, with Progress/Cancel throughout and one report that
// serialises to JSON (report_json.h).
//
//   ProcessOptions o;
//   o.decimate = true;
//   parseDecimateTarget("500k", o.decimation, err);   // or "10%", or o.decimation.maxError = 0.02
//   o.lodLevels = 3;
//   ProcessResult r = processMesh(std::move(*imported.mesh), o, &progress);
//   writeText("report.json", writeJson(toJson(r.report)));   // report_json.h
#include <string>
#include <vector>

#include "core/progress.h"
#include "mesh/mesh_data.h"
#include "meshproc/decimate.h"
#include "meshproc/error_metrics.h"
#include "meshproc/lod_chain.h"
#include "meshproc/max_error_refine.h"
#include "meshproc/mesh_clean.h"

namespace hs::mesh {

struct ProcessOptions {
  bool clean = true;
  CleanOptions cleaning;

  bool decimate = false;
  DecimateOptions decimation;
  // With a finite decimation.maxError the quadric estimate steers the
  // decimator; the measured Hausdorff decides. When it comes out above
  // maxError, decimation reruns with a proportionally tighter estimate
  // (halved when a run came no closer), at most this many extra times,
  // and the report says how many it took. Over 6,000 random defect
  // meshes (1,491 with a maximum error) 1.76-1.83 runs on average, at
  // most 5: 3 retries left 10 of them over the bound, 6 leave none.
  int maxErrorRetries = 6;

  // After each decimation run (and each LOD level), move the vertices
  // around the largest distances to lower it (max_error_refine.h: the
  // Hausdorff 7-36% lower for about half a measurement's time).
  bool refine = true;
  RefineOptions refinement;

  bool measureError = true;  // the error report for the decimated result
  ErrorOptions error;        // error.certify: a certified upper bound too, which judges maxError

  int lodLevels = 0;         // coarser levels after the result (lod_chain.h)
  double lodRatio = 0.25;
  // The LOD levels' error reports sample fewer points than the result's
  // (error.samplesPerFace, if that is lower, wins): a level's error only
  // picks it on screen, and at 2 samples a face the Hausdorff came within
  // 2.5% of that at 10 (the result's rate) and 5% of the densest measured,
  // on the bunny and a 2M-triangle scan tile, in 0.3-0.5 of the time
  // (bench_error_measure --convergence, docs/meshes.md).
  double lodSamplesPerFace = 2.0;
};

// ProcessOptions' parameters as the import offers them, declared once
// (`import`, the Import dialog): decimate_to (the CLI's text: 500k, 2M,
// 10%), target_ratio_pct and target_triangles (decimateTargetDecls()),
// max_error_m, lods, no_refine, certify, clean.
const std::vector<ParamDecl>& processOptionDecls();

struct LodSummary {
  size_t triangles = 0;
  double hausdorff = 0, hausdorffRel = 0;  // against level 0 (the processed mesh)
  double seconds = 0;                      // decimation, refinement and measurement
  double samplesPerFace = 0;               // its error report's rate (0: level 0, or not recorded)
};

struct ProcessReport {
  bool cleaned = false;
  CleanReport cleaning;
  bool decimated = false;
  DecimateReport decimation;
  int maxErrorPasses = 0;    // decimation runs made for maxError (1 = first try; if none met it, the closest is kept)
  bool refined = false;
  RefineReport refinement;   // of the kept run
  bool errorMeasured = false;
  ErrorReport error;         // original (after cleaning) -> decimated
  std::vector<LodSummary> lods;  // level 0 first
  double seconds = 0;
};

struct ProcessResult {
  MeshData mesh;             // the processed mesh (= LOD 0)
  std::vector<MeshData> lods;  // coarser levels, sharing `mesh`'s textures
  ProcessReport report;
  bool cancelled = false;
  std::string error;         // plain words; the report says what was found
  bool ok() const { return error.empty() && !cancelled; }
};

ProcessResult processMesh(MeshData input, const ProcessOptions& options, const Progress* progress = nullptr);

}  // namespace hs::mesh
