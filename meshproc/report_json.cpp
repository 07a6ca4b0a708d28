#include "meshproc/report_json.h"

#include <cmath>
#include <cstdio>

namespace hs::mesh {
namespace {

// Appends "key": value pairs to one object; nested objects are appended as
// already-serialised text.
class Object {
 public:
  Object& str(const char* key, const std::string& v) { return raw(key, quote(v)); }
  Object& num(const char* key, double v) {
    if (!std::isfinite(v)) return raw(key, "null");
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return raw(key, buf);
  }
  Object& count(const char* key, size_t v) { return raw(key, std::to_string(v)); }
  Object& flag(const char* key, bool v) { return raw(key, v ? "true" : "false"); }
  Object& raw(const char* key, const std::string& json) {
    text_ += (text_.empty() ? "" : ",") + quote(key) + ":" + json;
    return *this;
  }
  Object& strings(const char* key, const std::vector<std::string>& list) {
    std::string a = "[";
    for (size_t i = 0; i < list.size(); ++i) a += (i ? "," : "") + quote(list[i]);
    return raw(key, a + "]");
  }
  Object& indices(const char* key, const std::vector<uint32_t>& list) {
    std::string a = "[";
    for (size_t i = 0; i < list.size(); ++i) a += (i ? "," : "") + std::to_string(list[i]);
    return raw(key, a + "]");
  }
  std::string json() const { return "{" + text_ + "}"; }

  static std::string quote(const std::string& s) {
    std::string q = "\"";
    for (unsigned char c : s) {
      switch (c) {
        case '"': q += "\\\""; break;
        case '\\': q += "\\\\"; break;
        case '\n': q += "\\n"; break;
        case '\r': q += "\\r"; break;
        case '\t': q += "\\t"; break;
        default:
          if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            q += buf;
          } else {
            q += char(c);
          }
      }
    }
    return q + "\"";
  }

 private:
  std::string text_;
};

std::string vec3(const glm::dvec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%.6f,%.6f,%.6f]", v.x, v.y, v.z);
  return buf;
}

std::string distances(const DistanceStats& d, double diag) {
  auto rel = [&](double m) { return diag > 0 ? m / diag : 0.0; };
  return Object()
      .num("max_m", d.max).num("max_rel", rel(d.max))
      .num("mean_m", d.mean).num("rms_m", d.rms).num("p95_m", d.p95)
      .count("samples", d.samples)
      .json();
}

}  // namespace

std::string toJson(const ImportReport& r) {
  Object o;
  o.str("file", r.file).str("reader", r.reader)
      .count("vertices_in", r.verticesIn).count("triangles_in", r.trianglesIn)
      .count("vertices_out", r.verticesOut).count("triangles_out", r.trianglesOut)
      .count("non_finite_vertices", r.nonFiniteVertices).count("out_of_range_faces", r.outOfRangeFaces)
      .count("degenerate_faces", r.degenerateFaces).count("polygons_triangulated", r.polygonsTriangulated)
      .count("skipped_lines", r.skippedLines)
      .flag("normals_generated", r.normalsGenerated).flag("up_axis_converted", r.upAxisConverted);
  if (!r.geoOffsetSource.empty())
    o.raw("geo_offset", Object().raw("offset_m", vec3(r.geoOffset)).str("source", r.geoOffsetSource).str("crs", r.geoOffsetCrs).json());
  return o.strings("warnings", r.warnings).num("seconds", r.seconds).json();
}

std::string toJson(const CleanReport& r) {
  return Object()
      .count("vertices_in", r.verticesIn).count("triangles_in", r.trianglesIn)
      .count("vertices_out", r.verticesOut).count("triangles_out", r.trianglesOut)
      .count("non_finite_vertices_quarantined", r.nonFiniteVertices)
      .count("faces_on_non_finite_vertices_quarantined", r.facesOnNonFiniteVertices)
      .count("out_of_range_faces_quarantined", r.outOfRangeFaces)
      .count("duplicate_vertices_welded", r.duplicateVerticesWelded)
      .count("repeated_index_faces_removed", r.repeatedIndexFaces)
      .count("zero_area_faces_removed", r.zeroAreaFaces)
      .count("duplicate_faces_removed", r.duplicateFaces)
      .count("non_manifold_edges_split", r.nonManifoldEdges)
      .count("non_manifold_vertices_split", r.nonManifoldVertices)
      .count("vertices_added_by_split", r.verticesAddedBySplit)
      .count("faces_detached", r.facesDetached)
      .count("unused_vertices_removed", r.unusedVerticesRemoved)
      .indices("first_non_finite_vertices", r.nonFiniteVertexIndices)
      .indices("first_out_of_range_faces", r.outOfRangeFaceIndices)
      .indices("first_degenerate_faces", r.degenerateFaceIndices)
      .strings("warnings", r.warnings)
      .num("seconds", r.seconds)
      .json();
}

std::string toJson(const DecimateReport& r) {
  return Object()
      .count("triangles_in", r.trianglesIn).count("vertices_in", r.verticesIn)
      .count("triangles_out", r.trianglesOut).count("vertices_out", r.verticesOut)
      .count("target_triangles", r.targetTriangles).flag("target_reached", r.targetReached)
      .count("collapses", r.collapses)
      .count("rejected_topology", r.rejectedTopology).count("rejected_normal_flip", r.rejectedFlip)
      .count("rejected_sliver", r.rejectedSliver)
      .count("boundary_vertices", r.boundaryVertices).count("seam_vertices", r.seamVertices)
      .count("fixed_vertices", r.fixedVertices).count("locked_vertices", r.lockedVertices)
      .count("degenerate_faces_removed", r.degenerateFacesRemoved)
      .count("non_manifold_edges_split", r.nonManifold.nonManifoldEdges)
      .count("non_manifold_vertices_split", r.nonManifold.nonManifoldVertices)
      .num("max_estimated_error_m", r.maxEstimatedError)
      .count("regions", r.regions).count("threads", r.threads)
      .num("seconds_setup", r.secondsSetup).num("seconds_regions", r.secondsRegions)
      .num("seconds_border_pass", r.secondsBorders).num("seconds_output", r.secondsOutput)
      .num("seconds", r.secondsTotal)
      .json();
}

std::string toJson(const ErrorReport& r) {
  Object o;
  o.num("hausdorff_m", r.hausdorff).num("hausdorff_rel", r.rel(r.hausdorff))
      .num("mean_m", r.mean).num("mean_rel", r.rel(r.mean))
      .num("rms_m", r.rms).num("rms_rel", r.rel(r.rms))
      .num("p95_m", r.p95).num("p95_rel", r.rel(r.p95))
      .num("bbox_diagonal_m", r.bboxDiagonal)
      .raw("original_to_result", distances(r.forward, r.bboxDiagonal))
      .raw("result_to_original", distances(r.backward, r.bboxDiagonal))
      .num("samples_per_face", r.samplesPerFace).count("seed", r.seed)
      .count("flipped_normals", r.flippedNormals).count("faces_checked", r.facesChecked);
  if (r.uvMeasured)
    o.raw("uv_displacement_texels", Object()
                                        .num("max", r.uvMaxTexels).num("mean", r.uvMeanTexels).num("p95", r.uvP95Texels)
                                        .count("samples", r.uvSamples)
                                        .count("texture_width", size_t(r.textureWidth))
                                        .count("texture_height", size_t(r.textureHeight))
                                        .json());
  else
    o.raw("uv_displacement_texels", "null");
  return o.count("boundary_seam_vertices", r.constrainedVerticesOut)
      .count("boundary_seam_vertices_moved", r.constrainedVerticesMoved)
      .num("boundary_seam_max_deviation_m", r.constrainedMaxDeviation)
      .num("area_in_m2", r.areaIn).num("area_out_m2", r.areaOut)
      .num("area_change_rel", r.areaIn > 0 ? (r.areaOut - r.areaIn) / r.areaIn : 0.0)
      .num("volume_in_m3", r.volumeIn).num("volume_out_m3", r.volumeOut)
      .num("volume_change_rel", r.volumeIn != 0 ? (r.volumeOut - r.volumeIn) / std::abs(r.volumeIn) : 0.0)
      .count("non_manifold_edges_in", r.nonManifoldIn.edges).count("non_manifold_vertices_in", r.nonManifoldIn.vertices)
      .count("non_manifold_edges_out", r.nonManifoldOut.edges).count("non_manifold_vertices_out", r.nonManifoldOut.vertices)
      .num("seconds", r.seconds)
      .json();
}

std::string processReportJson(const ProcessReport& r, const ImportReport* import) {
  Object o;
  o.raw("import", import ? toJson(*import) : "null");
  o.raw("cleaning", r.cleaned ? toJson(r.cleaning) : "null");
  o.raw("decimation", r.decimated ? toJson(r.decimation) : "null");
  if (r.decimated) o.count("decimation_passes", size_t(r.maxErrorPasses));
  o.raw("error", r.errorMeasured ? toJson(r.error) : "null");
  std::string lods = "[";
  for (size_t i = 0; i < r.lods.size(); ++i)
    lods += (i ? "," : "") + Object()
                                 .count("level", i)
                                 .count("triangles", r.lods[i].triangles)
                                 .num("hausdorff_m", r.lods[i].hausdorff)
                                 .num("hausdorff_rel", r.lods[i].hausdorffRel)
                                 .num("seconds", r.lods[i].seconds)
                                 .json();
  o.raw("lods", lods + "]");
  return o.num("seconds", r.seconds).json() + "\n";
}

}  // namespace hs::mesh
