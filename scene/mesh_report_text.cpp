#include "scene/mesh_report_text.h"

#include <cmath>
#include <cstdio>
#include <optional>

#include "scene/asset_reports.h"

namespace hs::scene {
namespace {

// Number formats, each with its literal format string (checked by the compiler).
std::string g3(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}
std::string g4(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}
std::string signedG3(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%+.3g", v);
  return b;
}
std::string fixed3(double v) {
  char b[48];
  std::snprintf(b, sizeof b, "%.3f", v);
  return b;
}

// A value that was not finite (written as null) reads "n/a".
std::string fmt3(double v) { return std::isfinite(v) ? g3(v) : "n/a"; }
std::string metres(double v) { return std::isfinite(v) ? g4(v) + " m" : "n/a"; }
std::string seconds(double v) { return std::isfinite(v) ? fixed3(v) + " s" : "n/a"; }
std::string count(size_t v) { return std::to_string(v); }
// A fraction as a percentage ("0.12%"), signed when it is a change.
std::string percent(double v, bool sign = false) {
  if (!std::isfinite(v)) return "n/a";
  return (sign ? signedG3(v * 100.0) : g3(v * 100.0)) + "%";
}

struct Rows {
  ReportSection s;
  explicit Rows(std::string title) { s.title = std::move(title); }
  Rows& add(std::string key, std::string label, std::string value) {
    s.rows.push_back({std::move(key), std::move(label), std::move(value)});
    return *this;
  }
};

ReportSection errorSection(const mesh::ErrorReport& e) {
  Rows r("Error (result against the cleaned original)");
  r.add("hausdorff_m", "Hausdorff distance (symmetric)", metres(e.hausdorff))
      .add("hausdorff_rel", "Hausdorff, of the bounding-box diagonal", percent(e.rel(e.hausdorff)))
      .add("mean_m", "Mean distance", metres(e.mean))
      .add("rms_m", "RMS distance", metres(e.rms))
      .add("p95_m", "95th percentile distance", metres(e.p95))
      .add("flipped_normals", "Flipped normals", count(e.flippedNormals) + " of " + count(e.facesChecked) + " faces");
  if (e.certified)
    r.add("hausdorff_certified", "Hausdorff, certified at most",
          metres(e.hausdorffUpper) + " (" + percent(e.rel(e.hausdorffUpper)) + "; the true one lies between " +
              metres(e.hausdorff) + " and this), " + seconds(e.certifySeconds));
  if (e.uvMeasured) {
    r.add("uv_displacement_texels", "UV displacement (max / mean / p95)",
          fmt3(e.uvMaxTexels) + " / " + fmt3(e.uvMeanTexels) + " / " + fmt3(e.uvP95Texels) + " texels");
  } else {
    r.add("uv_displacement_texels", "UV displacement", "not measured (no UVs or no texture)");
  }
  r.add("boundary_seam_vertices_moved", "Boundary/seam vertices moved",
        count(e.constrainedVerticesMoved) + " of " + count(e.constrainedVerticesOut))
      .add("area_change_rel", "Area change", percent(e.areaChangeRel(), true))
      .add("volume_change_rel", "Volume change", percent(e.volumeChangeRel(), true))
      .add("non_manifold_edges_in", "Non-manifold edges (in -> out)",
           count(e.nonManifoldIn.edges) + " -> " + count(e.nonManifoldOut.edges))
      .add("non_manifold_vertices_in", "Non-manifold vertices (in -> out)",
           count(e.nonManifoldIn.vertices) + " -> " + count(e.nonManifoldOut.vertices))
      .add("samples_per_face", "Samples per original face", fmt3(e.samplesPerFace))
      .add("seconds", "Measurement time", seconds(e.seconds));
  return r.s;
}

// Whether the result met the maximum error asked for; nothing when none
// was asked (or the result was not measured). Follows from the stored
// options and the measured error, so older reports answer too.
std::optional<bool> maxErrorMet(const AssetProcessReport& a) {
  const double wanted = a.options.decimation.maxError;
  if (!a.report.decimated || !a.report.errorMeasured || !std::isfinite(wanted) || !(wanted > 0)) return std::nullopt;
  const mesh::ErrorReport& e = a.report.error;
  return (e.certified ? e.hausdorffUpper : e.hausdorff) <= wanted;
}

ReportSection decimationSection(const AssetProcessReport& a) {
  const mesh::ProcessReport& p = a.report;
  const mesh::DecimateReport& d = p.decimation;
  Rows r("Decimation");
  r.add("triangles_in", "Triangles in", count(d.trianglesIn))
      .add("triangles_out", "Triangles out", count(d.trianglesOut))
      .add("target_triangles", "Target",
           count(d.targetTriangles) + (d.targetReached ? " (reached)" : " (stopped by the error bound or the mesh)"))
      .add("collapses", "Edge collapses", count(d.collapses))
      .add("rejected_normal_flip", "Collapses refused (flip / sliver / topology)",
           count(d.rejectedFlip) + " / " + count(d.rejectedSliver) + " / " + count(d.rejectedTopology));
  if (const std::optional<bool> met = maxErrorMet(a))
    r.add("max_error_m", "Maximum error asked",
          metres(a.options.decimation.maxError) +
              (*met ? (p.error.certified ? " (met, certified)" : " (met)")
                    : " (NOT met: the run measured closest to it is kept)"));
  if (p.maxErrorPasses > 1)
    r.add("decimation_passes", "Runs for the maximum error", std::to_string(p.maxErrorPasses));
  r.add("seconds", "Decimation time", seconds(d.secondsTotal));
  if (p.refined) {
    const mesh::RefineReport& f = p.refinement;
    r.add("refinement", "Vertices refined (minimax)",
          count(f.moved) + " moved of " + count(f.candidates) + " near the largest distance, sampled " +
              metres(f.largestBefore) + " -> " + metres(f.largestAfter) + ", " + seconds(f.seconds));
  }
  return r.s;
}

ReportSection cleaningSection(const mesh::CleanReport& c) {
  Rows r("Cleaning");
  r.add("duplicate_vertices_welded", "Duplicate vertices welded", count(c.duplicateVerticesWelded))
      .add("zero_area_faces_removed", "Zero-area faces removed", count(c.zeroAreaFaces))
      .add("repeated_index_faces_removed", "Faces repeating a vertex removed", count(c.repeatedIndexFaces))
      .add("duplicate_faces_removed", "Duplicate faces removed", count(c.duplicateFaces))
      .add("non_finite_vertices_quarantined", "NaN/Inf vertices quarantined", count(c.nonFiniteVertices))
      .add("out_of_range_faces_quarantined", "Faces with bad indices quarantined", count(c.outOfRangeFaces))
      .add("non_manifold_edges_split", "Non-manifold edges split", count(c.nonManifoldEdges))
      .add("non_manifold_vertices_split", "Non-manifold vertices split", count(c.nonManifoldVertices))
      .add("triangles_out", "Triangles after cleaning", count(c.trianglesOut))
      .add("seconds", "Cleaning time", seconds(c.seconds));
  return r.s;
}

ReportSection lodSection(const std::vector<mesh::LodSummary>& lods) {
  Rows r("LODs");
  for (size_t level = 0; level < lods.size(); ++level) {
    const mesh::LodSummary& l = lods[level];
    r.add("lods[" + std::to_string(level) + "]", "Level " + std::to_string(level),
          count(l.triangles) + " triangles, hausdorff_m " + metres(l.hausdorff) + " (" + percent(l.hausdorffRel) +
              "), " + seconds(l.seconds) +
              (l.samplesPerFace > 0 ? ", " + fmt3(l.samplesPerFace) + " samples per face" : std::string()));
  }
  return r.s;
}

ReportSection tilesSection(const TileWeldReport& t) {
  Rows r("Tiles");
  r.add("files", "Tiles", count(t.files))
      .add("border_vertices", "Border vertices", count(t.borderVertices))
      .add("border_vertices_snapped", "Snapped onto a neighbour", count(t.borderVerticesSnapped))
      .add("border_vertices_merged", "Merged with it", count(t.borderVerticesMerged))
      .add("weld_tolerance_m", "Weld tolerance", metres(t.weldTolerance));
  return r.s;
}

}  // namespace

std::vector<ReportSection> processReportSections(const Json& json) {
  const std::optional<AssetProcessReport> stored = readProcessReport(json);
  std::vector<ReportSection> out;
  if (!stored) return out;
  const mesh::ProcessReport& p = stored->report;
  if (p.errorMeasured) out.push_back(errorSection(p.error));
  if (p.decimated) out.push_back(decimationSection(*stored));
  if (!p.lods.empty()) out.push_back(lodSection(p.lods));
  if (p.cleaned) out.push_back(cleaningSection(p.cleaning));
  if (stored->tiles) out.push_back(tilesSection(*stored->tiles));
  Rows total("Total");
  total.add("seconds", "Processing time", seconds(p.seconds));
  out.push_back(total.s);
  return out;
}

std::string processReportSummary(const Json& json) {
  const std::optional<AssetProcessReport> stored = readProcessReport(json);
  if (!stored) return {};
  const mesh::ProcessReport& p = stored->report;
  std::string s;
  if (p.decimated) {
    s = "decimated " + count(p.decimation.trianglesIn) + " -> " + count(p.decimation.trianglesOut) + " triangles";
  } else if (p.cleaned) {
    s = "cleaned, " + count(p.cleaning.trianglesOut) + " triangles";
  } else {
    s = "as imported";
  }
  if (p.errorMeasured) {
    const mesh::ErrorReport& e = p.error;
    s += ", hausdorff_m " + metres(e.hausdorff) + " (" + percent(e.rel(e.hausdorff)) + " of the diagonal), mean_m " +
         metres(e.mean) + ", p95_m " + metres(e.p95) + ", flipped_normals " + count(e.flippedNormals);
    if (e.certified) s += ", certified at most " + metres(e.hausdorffUpper);
  }
  const size_t levels = p.lods.size();
  if (levels > 1) s += ", " + std::to_string(levels - 1) + " LOD level" + (levels > 2 ? "s" : "");
  s += ", " + seconds(p.seconds);
  return s;
}

std::vector<std::string> processWarnings(const Json& json) {
  std::vector<std::string> out;
  const std::optional<AssetProcessReport> stored = readProcessReport(json);
  if (!stored) return out;
  const mesh::ProcessReport& p = stored->report;
  if (maxErrorMet(*stored) == false)
    out.push_back("the maximum error of " + metres(stored->options.decimation.maxError) +
                  " was not met: " + std::to_string(p.maxErrorPasses) +
                  " decimation runs measured above it; the closest (hausdorff_m " + metres(p.error.hausdorff) +
                  (p.error.certified ? ", certified at most " + metres(p.error.hausdorffUpper) : std::string()) +
                  ") is kept");
  return out;
}

}  // namespace hs::scene
