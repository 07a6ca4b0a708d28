#include "scene/mesh_report_text.h"

#include <cstdio>

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>

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
std::string fixed(double v, bool threeDecimals) {
  char b[48];
  if (threeDecimals) std::snprintf(b, sizeof b, "%.3f", v);
  else std::snprintf(b, sizeof b, "%.0f", v);
  return b;
}

std::string fmt3(double v) { return g3(v); }
std::string metres(const QJsonValue& v) { return v.isDouble() ? g4(v.toDouble()) + " m" : "n/a"; }
std::string seconds(const QJsonValue& v) { return v.isDouble() ? fixed(v.toDouble(), true) + " s" : "n/a"; }
std::string count(const QJsonValue& v) { return v.isDouble() ? fixed(v.toDouble(), false) : "n/a"; }
// A fraction as a percentage ("0.12%"), signed when it is a change.
std::string percent(const QJsonValue& v, bool sign = false) {
  if (!v.isDouble()) return "n/a";
  return (sign ? signedG3(v.toDouble() * 100.0) : g3(v.toDouble() * 100.0)) + "%";
}

struct Rows {
  ReportSection s;
  explicit Rows(std::string title) { s.title = std::move(title); }
  Rows& add(std::string key, std::string label, std::string value) {
    s.rows.push_back({std::move(key), std::move(label), std::move(value)});
    return *this;
  }
};

ReportSection errorSection(const QJsonObject& e) {
  Rows r("Error (result against the cleaned original)");
  r.add("hausdorff_m", "Hausdorff distance (symmetric)", metres(e["hausdorff_m"]))
      .add("hausdorff_rel", "Hausdorff, of the bounding-box diagonal", percent(e["hausdorff_rel"]))
      .add("mean_m", "Mean distance", metres(e["mean_m"]))
      .add("rms_m", "RMS distance", metres(e["rms_m"]))
      .add("p95_m", "95th percentile distance", metres(e["p95_m"]))
      .add("flipped_normals", "Flipped normals",
           count(e["flipped_normals"]) + " of " + count(e["faces_checked"]) + " faces");
  const QJsonValue uv = e["uv_displacement_texels"];
  if (uv.isObject()) {
    const QJsonObject u = uv.toObject();
    r.add("uv_displacement_texels", "UV displacement (max / mean / p95)",
          fmt3(u["max"].toDouble()) + " / " + fmt3(u["mean"].toDouble()) + " / " + fmt3(u["p95"].toDouble()) +
              " texels");
  } else {
    r.add("uv_displacement_texels", "UV displacement", "not measured (no UVs or no texture)");
  }
  r.add("boundary_seam_vertices_moved", "Boundary/seam vertices moved",
        count(e["boundary_seam_vertices_moved"]) + " of " + count(e["boundary_seam_vertices"]))
      .add("area_change_rel", "Area change", percent(e["area_change_rel"], true))
      .add("volume_change_rel", "Volume change", percent(e["volume_change_rel"], true))
      .add("non_manifold_edges_in", "Non-manifold edges (in -> out)",
           count(e["non_manifold_edges_in"]) + " -> " + count(e["non_manifold_edges_out"]))
      .add("non_manifold_vertices_in", "Non-manifold vertices (in -> out)",
           count(e["non_manifold_vertices_in"]) + " -> " + count(e["non_manifold_vertices_out"]))
      .add("samples_per_face", "Samples per original face", fmt3(e["samples_per_face"].toDouble()))
      .add("seconds", "Measurement time", seconds(e["seconds"]));
  return r.s;
}

ReportSection decimationSection(const QJsonObject& d, const QJsonObject& root) {
  Rows r("Decimation");
  r.add("triangles_in", "Triangles in", count(d["triangles_in"]))
      .add("triangles_out", "Triangles out", count(d["triangles_out"]))
      .add("target_triangles", "Target", count(d["target_triangles"]) +
                                             (d["target_reached"].toBool() ? " (reached)" : " (stopped by the error bound or the mesh)"))
      .add("collapses", "Edge collapses", count(d["collapses"]))
      .add("rejected_normal_flip", "Collapses refused (flip / sliver / topology)",
           count(d["rejected_normal_flip"]) + " / " + count(d["rejected_sliver"]) + " / " + count(d["rejected_topology"]));
  if (root["decimation_passes"].toInt() > 1)
    r.add("decimation_passes", "Runs to meet the maximum error", count(root["decimation_passes"]));
  r.add("seconds", "Decimation time", seconds(d["seconds"]));
  return r.s;
}

ReportSection cleaningSection(const QJsonObject& c) {
  Rows r("Cleaning");
  r.add("duplicate_vertices_welded", "Duplicate vertices welded", count(c["duplicate_vertices_welded"]))
      .add("zero_area_faces_removed", "Zero-area faces removed", count(c["zero_area_faces_removed"]))
      .add("repeated_index_faces_removed", "Faces repeating a vertex removed", count(c["repeated_index_faces_removed"]))
      .add("duplicate_faces_removed", "Duplicate faces removed", count(c["duplicate_faces_removed"]))
      .add("non_finite_vertices_quarantined", "NaN/Inf vertices quarantined", count(c["non_finite_vertices_quarantined"]))
      .add("out_of_range_faces_quarantined", "Faces with bad indices quarantined", count(c["out_of_range_faces_quarantined"]))
      .add("non_manifold_edges_split", "Non-manifold edges split", count(c["non_manifold_edges_split"]))
      .add("non_manifold_vertices_split", "Non-manifold vertices split", count(c["non_manifold_vertices_split"]))
      .add("triangles_out", "Triangles after cleaning", count(c["triangles_out"]))
      .add("seconds", "Cleaning time", seconds(c["seconds"]));
  return r.s;
}

ReportSection lodSection(const QJsonArray& lods) {
  Rows r("LODs");
  for (const QJsonValue& v : lods) {
    const QJsonObject l = v.toObject();
    const int level = l["level"].toInt();
    r.add("lods[" + std::to_string(level) + "]", "Level " + std::to_string(level),
          count(l["triangles"]) + " triangles, hausdorff_m " + metres(l["hausdorff_m"]) + " (" +
              percent(l["hausdorff_rel"]) + "), " + seconds(l["seconds"]));
  }
  return r.s;
}

ReportSection tilesSection(const QJsonObject& t) {
  Rows r("Tiles");
  r.add("files", "Tiles", count(t["files"]))
      .add("border_vertices", "Border vertices", count(t["border_vertices"]))
      .add("border_vertices_snapped", "Snapped onto a neighbour", count(t["border_vertices_snapped"]))
      .add("border_vertices_merged", "Merged with it", count(t["border_vertices_merged"]))
      .add("weld_tolerance_m", "Weld tolerance", metres(t["weld_tolerance_m"]));
  return r.s;
}

QJsonObject parse(const std::string& json) {
  if (json.empty()) return {};
  return QJsonDocument::fromJson(QByteArray::fromStdString(json)).object();
}

}  // namespace

std::vector<ReportSection> processReportSections(const std::string& json) {
  const QJsonObject o = parse(json);
  std::vector<ReportSection> out;
  if (o.isEmpty()) return out;
  if (o["error"].isObject()) out.push_back(errorSection(o["error"].toObject()));
  if (o["decimation"].isObject()) out.push_back(decimationSection(o["decimation"].toObject(), o));
  if (o["lods"].isArray() && !o["lods"].toArray().isEmpty()) out.push_back(lodSection(o["lods"].toArray()));
  if (o["cleaning"].isObject()) out.push_back(cleaningSection(o["cleaning"].toObject()));
  if (o["tiles"].isObject()) out.push_back(tilesSection(o["tiles"].toObject()));
  Rows total("Total");
  total.add("seconds", "Processing time", seconds(o["seconds"]));
  out.push_back(total.s);
  return out;
}

std::string processReportSummary(const std::string& json) {
  const QJsonObject o = parse(json);
  if (o.isEmpty()) return {};
  std::string s;
  if (o["decimation"].isObject()) {
    const QJsonObject d = o["decimation"].toObject();
    s = "decimated " + count(d["triangles_in"]) + " -> " + count(d["triangles_out"]) + " triangles";
  } else if (o["cleaning"].isObject()) {
    s = "cleaned, " + count(o["cleaning"].toObject()["triangles_out"]) + " triangles";
  } else {
    s = "as imported";
  }
  if (o["error"].isObject()) {
    const QJsonObject e = o["error"].toObject();
    s += ", hausdorff_m " + metres(e["hausdorff_m"]) + " (" + percent(e["hausdorff_rel"]) +
         " of the diagonal), mean_m " + metres(e["mean_m"]) + ", p95_m " + metres(e["p95_m"]) + ", flipped_normals " +
         count(e["flipped_normals"]);
  }
  const int levels = int(o["lods"].toArray().size());
  if (levels > 1) s += ", " + std::to_string(levels - 1) + " LOD level" + (levels > 2 ? "s" : "");
  s += ", " + seconds(o["seconds"]);
  return s;
}

}  // namespace hs::scene
