#include "scene/report_json.h"

#include <QJsonArray>
#include <QJsonDocument>

namespace hs::scene {

QJsonObject importReportToJsonObject(const mesh::ImportReport& r) {
  QJsonObject o;
  o["file"] = QString::fromStdString(r.file);
  o["reader"] = QString::fromStdString(r.reader);
  o["vertices_in"] = double(r.verticesIn);
  o["triangles_in"] = double(r.trianglesIn);
  o["vertices_out"] = double(r.verticesOut);
  o["triangles_out"] = double(r.trianglesOut);
  o["non_finite_vertices"] = double(r.nonFiniteVertices);
  o["out_of_range_faces"] = double(r.outOfRangeFaces);
  o["degenerate_faces"] = double(r.degenerateFaces);
  o["polygons_triangulated"] = double(r.polygonsTriangulated);
  o["skipped_primitives"] = double(r.skippedLines);
  o["normals_generated"] = r.normalsGenerated;
  o["up_axis_converted"] = r.upAxisConverted;
  o["seconds"] = r.seconds;
  // The georeferencing offset added to the mesh's origin, and where it came from.
  if (!r.geoOffsetSource.empty()) {
    QJsonObject g;
    g["offset_m"] = QJsonArray{r.geoOffset.x, r.geoOffset.y, r.geoOffset.z};
    g["source"] = QString::fromStdString(r.geoOffsetSource);
    g["crs"] = QString::fromStdString(r.geoOffsetCrs);
    o["geo_offset"] = g;
  }
  QJsonArray w;
  for (const auto& s : r.warnings) w.append(QString::fromStdString(s));
  o["warnings"] = w;
  return o;
}

std::string importReportToJson(const mesh::ImportReport& report) {
  return QJsonDocument(importReportToJsonObject(report)).toJson(QJsonDocument::Compact).toStdString();
}

}  // namespace hs::scene
