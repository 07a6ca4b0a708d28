#include "meshproc/report_json.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace hs::mesh {
namespace {

// Each report's members are declared once, by a function template over an
// IO (Writer or Reader) and the report (const when writing):
//
//   io.count(key, r.member [, old key])   whole number >= 0
//   io.number(key, r.member [, old key])  double (null when not finite)
//   io.flag / io.text / io.texts / io.indices / io.vec3
//   io.derived(key, fn)                   written from other members, not read
//   io.object(key, fields)                an object that is always there
//   io.optional(key, present, fields)     an object written only when `present`
//   io.nullable(key, flag, fields)        an object, or null when `flag` is false
//   io.list(key, items, fields)           an array of objects
//
// so the writer and the reader cannot disagree on a key or a type.

class Writer {
 public:
  Json out = Json::object();

  template <class T>
  void count(const char* key, const T& v, const char* /*oldKey*/ = nullptr) {
    out[key] = v;
  }
  void number(const char* key, double v, const char* /*oldKey*/ = nullptr) { out[key] = num(v); }
  void flag(const char* key, bool v) { out[key] = v; }
  void text(const char* key, const std::string& v) { out[key] = v; }
  void texts(const char* key, const std::vector<std::string>& v) { out[key] = v; }
  void indices(const char* key, const std::vector<uint32_t>& v) { out[key] = v; }
  void vec3(const char* key, const glm::dvec3& v) { out[key] = Json::array({num(v.x), num(v.y), num(v.z)}); }
  template <class F>
  void derived(const char* key, F value) {
    const auto v = value();
    if constexpr (std::is_floating_point_v<decltype(v)>) out[key] = num(v);
    else out[key] = v;
  }
  template <class F>
  void object(const char* key, F fields) {
    out[key] = sub(fields);
  }
  template <class F>
  void optional(const char* key, bool present, F fields) {
    if (present) out[key] = sub(fields);
  }
  template <class F>
  void nullable(const char* key, bool present, F fields) {
    out[key] = present ? sub(fields) : Json();
  }
  template <class T, class F>
  void list(const char* key, const std::vector<T>& items, F fields) {
    Json a = Json::array();
    for (size_t i = 0; i < items.size(); ++i) a.push_back(sub([&](Writer& w) { fields(w, items[i], i); }));
    out[key] = std::move(a);
  }

 private:
  // JSON has no NaN or infinity; a reader gets NaN back (Reader::number).
  static Json num(double v) { return std::isfinite(v) ? Json(v) : Json(); }
  template <class F>
  static Json sub(F fields) {
    Writer w;
    fields(w);
    return std::move(w.out);
  }
};

// Reads the members a schema declares from one object. Absent members keep
// their defaults; the first bad one fails `r` with its path, and ok() stays
// false from then on.
class Reader {
 public:
  Reader(JsonReader& r, const Json& obj, std::string path) : r_(r), obj_(obj), path_(std::move(path)) {}
  bool ok() const { return ok_; }

  template <class T>
  void count(const char* key, T& v, const char* oldKey = nullptr) {
    const char* at = key;
    const Json* m = JsonReader::member(obj_, key);
    if (!m && oldKey) m = JsonReader::member(obj_, at = oldKey);
    if (!m) return;
    constexpr auto hi = std::min<uint64_t>(uint64_t(std::numeric_limits<T>::max()), uint64_t(INT64_MAX));
    int64_t i = 0;
    if (check(r_.integer(*m, jsonPath(path_, at), i, 0, int64_t(hi)))) v = T(i);
  }
  void number(const char* key, double& v, const char* oldKey = nullptr) {
    const char* at = key;
    const Json* m = JsonReader::member(obj_, key);
    if (!m && oldKey) m = JsonReader::member(obj_, at = oldKey);
    if (!m) return;
    if (m->is_null()) v = std::numeric_limits<double>::quiet_NaN();  // written for a value that was not finite
    else check(r_.number(*m, jsonPath(path_, at), v));
  }
  void flag(const char* key, bool& v) { check(r_.optBoolean(obj_, path_, key, v)); }
  void text(const char* key, std::string& v) { check(r_.optString(obj_, path_, key, v)); }
  void texts(const char* key, std::vector<std::string>& v) {
    each(key, v, [&](const Json& x, const std::string& p, std::string& out) { return r_.string(x, p, out); });
  }
  void indices(const char* key, std::vector<uint32_t>& v) {
    each(key, v, [&](const Json& x, const std::string& p, uint32_t& out) {
      int64_t i = 0;
      if (!r_.integer(x, p, i, 0, UINT32_MAX)) return false;
      out = uint32_t(i);
      return true;
    });
  }
  void vec3(const char* key, glm::dvec3& v) {
    const Json* m = JsonReader::member(obj_, key);
    if (!m) return;
    const std::string p = jsonPath(path_, key);
    if (!m->is_array() || m->size() != 3) {
      check(r_.fail(p, std::string("expected [x, y, z], not ") + jsonTypeName(*m)));
      return;
    }
    for (int i = 0; i < 3; ++i) {
      const Json& c = (*m)[size_t(i)];
      if (c.is_null()) v[i] = std::numeric_limits<double>::quiet_NaN();  // as number() reads null
      else check(r_.number(c, jsonIndex(p, size_t(i)), v[i]));
    }
  }
  template <class F>
  void derived(const char*, F) {}
  template <class F>
  void object(const char* key, F fields) {
    if (const Json* m = JsonReader::member(obj_, key)) sub(*m, jsonPath(path_, key), fields);
  }
  template <class F>
  void optional(const char* key, bool /*present: decided by what is read*/, F fields) {
    const Json* m = JsonReader::member(obj_, key);
    if (m && !m->is_null()) sub(*m, jsonPath(path_, key), fields);
  }
  template <class F>
  void nullable(const char* key, bool& present, F fields) {
    const Json* m = JsonReader::member(obj_, key);
    if (!m) return;
    present = !m->is_null();
    if (present) sub(*m, jsonPath(path_, key), fields);
  }
  template <class T, class F>
  void list(const char* key, std::vector<T>& items, F fields) {
    const Json* m = JsonReader::member(obj_, key);
    if (!m) return;
    const std::string p = jsonPath(path_, key);
    if (!check(r_.array(*m, p))) return;
    items.clear();
    for (size_t i = 0; i < m->size() && ok_; ++i) {
      T item{};
      sub((*m)[i], jsonIndex(p, i), [&](Reader& rd) { fields(rd, item, i); });
      items.push_back(std::move(item));
    }
  }

 private:
  bool check(bool good) {
    ok_ = ok_ && good;
    return good;
  }
  template <class T, class ReadOne>
  void each(const char* key, std::vector<T>& v, ReadOne readOne) {
    const Json* m = JsonReader::member(obj_, key);
    if (!m) return;
    const std::string p = jsonPath(path_, key);
    if (!check(r_.array(*m, p))) return;
    v.assign(m->size(), T{});
    for (size_t i = 0; i < m->size() && ok_; ++i) check(readOne((*m)[i], jsonIndex(p, i), v[i]));
  }
  template <class F>
  void sub(const Json& m, const std::string& path, F fields) {
    if (!check(r_.object(m, path))) return;
    Reader rd(r_, m, path);
    fields(rd);
    check(rd.ok());
  }

  JsonReader& r_;
  const Json& obj_;
  std::string path_;
  bool ok_ = true;
};

// --- the schemas --------------------------------------------------------------

template <class IO, class R>
void importFields(IO& io, R& r) {
  io.text("file", r.file);
  io.text("reader", r.reader);
  io.count("vertices_in", r.verticesIn);
  io.count("triangles_in", r.trianglesIn);
  io.count("vertices_out", r.verticesOut);
  io.count("triangles_out", r.trianglesOut);
  io.count("non_finite_vertices", r.nonFiniteVertices);
  io.count("out_of_range_faces", r.outOfRangeFaces);
  io.count("degenerate_faces", r.degenerateFaces);
  io.count("polygons_triangulated", r.polygonsTriangulated);
  // Lines, points and other primitives no triangles came from, in any
  // format; this library's writer called it "skipped_lines" before the
  // import report had one schema, and that name is still read.
  io.count("skipped_primitives", r.skippedLines, "skipped_lines");
  // What the file declares (STL count, PLY header, glTF accessors), when it
  // declares something: compare with triangles_out.
  io.optional("declared", !r.declaredBy.empty(), [&](auto& d) {
    d.count("triangles", r.declaredTriangles);
    d.text("by", r.declaredBy);
  });
  io.flag("normals_generated", r.normalsGenerated);
  io.flag("up_axis_converted", r.upAxisConverted);
  // The georeferencing offset added to the mesh's origin, and where it came from.
  io.optional("geo_offset", !r.geoOffsetSource.empty(), [&](auto& g) {
    g.vec3("offset_m", r.geoOffset);
    g.text("source", r.geoOffsetSource);
    g.text("crs", r.geoOffsetCrs);
  });
  io.texts("warnings", r.warnings);
  io.number("seconds", r.seconds);
}

template <class IO, class R>
void cleanFields(IO& io, R& r) {
  io.count("vertices_in", r.verticesIn);
  io.count("triangles_in", r.trianglesIn);
  io.count("vertices_out", r.verticesOut);
  io.count("triangles_out", r.trianglesOut);
  io.count("non_finite_vertices_quarantined", r.nonFiniteVertices);
  io.count("faces_on_non_finite_vertices_quarantined", r.facesOnNonFiniteVertices);
  io.count("out_of_range_faces_quarantined", r.outOfRangeFaces);
  io.count("duplicate_vertices_welded", r.duplicateVerticesWelded);
  io.count("repeated_index_faces_removed", r.repeatedIndexFaces);
  io.count("zero_area_faces_removed", r.zeroAreaFaces);
  io.count("duplicate_faces_removed", r.duplicateFaces);
  io.count("non_manifold_edges_split", r.nonManifoldEdges);
  io.count("non_manifold_vertices_split", r.nonManifoldVertices);
  io.count("vertices_added_by_split", r.verticesAddedBySplit);
  io.count("faces_detached", r.facesDetached);
  io.count("unused_vertices_removed", r.unusedVerticesRemoved);
  io.indices("first_non_finite_vertices", r.nonFiniteVertexIndices);
  io.indices("first_out_of_range_faces", r.outOfRangeFaceIndices);
  io.indices("first_degenerate_faces", r.degenerateFaceIndices);
  io.texts("warnings", r.warnings);
  io.number("seconds", r.seconds);
}

template <class IO, class R>
void decimateFields(IO& io, R& r) {
  io.count("triangles_in", r.trianglesIn);
  io.count("vertices_in", r.verticesIn);
  io.count("triangles_out", r.trianglesOut);
  io.count("vertices_out", r.verticesOut);
  io.count("target_triangles", r.targetTriangles);
  io.flag("target_reached", r.targetReached);
  io.count("collapses", r.collapses);
  io.count("rejected_topology", r.rejectedTopology);
  io.count("rejected_normal_flip", r.rejectedFlip);
  io.count("rejected_sliver", r.rejectedSliver);
  io.count("boundary_vertices", r.boundaryVertices);
  io.count("seam_vertices", r.seamVertices);
  io.count("fixed_vertices", r.fixedVertices);
  io.count("locked_vertices", r.lockedVertices);
  io.count("degenerate_faces_removed", r.degenerateFacesRemoved);
  io.count("non_manifold_edges_split", r.nonManifold.nonManifoldEdges);
  io.count("non_manifold_vertices_split", r.nonManifold.nonManifoldVertices);
  io.number("max_estimated_error_m", r.maxEstimatedError);
  io.count("regions", r.regions);
  io.count("threads", r.threads);
  io.count("rounds", r.rounds);
  io.count("levels", r.levels);
  io.count("last_region_collapses", r.lastRegionCollapses);
  io.number("seconds_setup", r.secondsSetup);
  io.number("seconds_regions", r.secondsRegions);
  // Reports written before region levels replaced the serial border pass
  // (issue 11) name the last region's time after that pass.
  io.number("seconds_last_region", r.secondsLastRegion, "seconds_border_pass");
  io.number("seconds_output", r.secondsOutput);
  io.number("seconds", r.secondsTotal);
}

// One direction's distances; `diagonal` for the relative maximum.
template <class IO, class D>
void distanceFields(IO& io, D& d, double diagonal) {
  io.number("max_m", d.max);
  io.derived("max_rel", [&] { return diagonal > 0 ? d.max / diagonal : 0.0; });
  io.number("mean_m", d.mean);
  io.number("rms_m", d.rms);
  io.number("p95_m", d.p95);
  io.count("samples", d.samples);
}

template <class IO, class R>
void errorFields(IO& io, R& r) {
  io.number("hausdorff_m", r.hausdorff);
  io.derived("hausdorff_rel", [&] { return r.rel(r.hausdorff); });
  io.number("mean_m", r.mean);
  io.derived("mean_rel", [&] { return r.rel(r.mean); });
  io.number("rms_m", r.rms);
  io.derived("rms_rel", [&] { return r.rel(r.rms); });
  io.number("p95_m", r.p95);
  io.derived("p95_rel", [&] { return r.rel(r.p95); });
  io.number("bbox_diagonal_m", r.bboxDiagonal);
  io.object("original_to_result", [&](auto& d) { distanceFields(d, r.forward, r.bboxDiagonal); });
  io.object("result_to_original", [&](auto& d) { distanceFields(d, r.backward, r.bboxDiagonal); });
  io.number("samples_per_face", r.samplesPerFace);
  io.count("seed", r.seed);
  io.nullable("hausdorff_certified", r.certified, [&](auto& c) {
    c.number("upper_m", r.hausdorffUpper);
    c.derived("upper_rel", [&] { return r.rel(r.hausdorffUpper); });
    c.count("pieces", r.certifiedPieces);
    c.number("seconds", r.certifySeconds);
  });
  io.count("flipped_normals", r.flippedNormals);
  io.count("faces_checked", r.facesChecked);
  io.nullable("uv_displacement_texels", r.uvMeasured, [&](auto& u) {
    u.number("max", r.uvMaxTexels);
    u.number("mean", r.uvMeanTexels);
    u.number("p95", r.uvP95Texels);
    u.count("samples", r.uvSamples);
    u.count("texture_width", r.textureWidth);
    u.count("texture_height", r.textureHeight);
  });
  io.count("boundary_seam_vertices", r.constrainedVerticesOut);
  io.count("boundary_seam_vertices_moved", r.constrainedVerticesMoved);
  io.number("boundary_seam_max_deviation_m", r.constrainedMaxDeviation);
  io.number("area_in_m2", r.areaIn);
  io.number("area_out_m2", r.areaOut);
  io.derived("area_change_rel", [&] { return r.areaChangeRel(); });
  io.number("volume_in_m3", r.volumeIn);
  io.number("volume_out_m3", r.volumeOut);
  io.derived("volume_change_rel", [&] { return r.volumeChangeRel(); });
  io.count("non_manifold_edges_in", r.nonManifoldIn.edges);
  io.count("non_manifold_vertices_in", r.nonManifoldIn.vertices);
  io.count("non_manifold_edges_out", r.nonManifoldOut.edges);
  io.count("non_manifold_vertices_out", r.nonManifoldOut.vertices);
  io.number("seconds", r.seconds);
}

template <class IO, class R>
void refineFields(IO& io, R& r) {
  io.count("candidates", r.candidates);
  io.count("moved", r.moved);
  io.count("iterations", r.iterations);
  io.number("largest_before_m", r.largestBefore);
  io.number("largest_after_m", r.largestAfter);
  io.number("seconds", r.seconds);
}

template <class IO, class R>
void processFields(IO& io, R& r) {
  io.nullable("cleaning", r.cleaned, [&](auto& c) { cleanFields(c, r.cleaning); });
  io.nullable("decimation", r.decimated, [&](auto& d) { decimateFields(d, r.decimation); });
  if (r.decimated) io.count("decimation_passes", r.maxErrorPasses);
  io.nullable("refinement", r.refined, [&](auto& f) { refineFields(f, r.refinement); });
  io.nullable("error", r.errorMeasured, [&](auto& e) { errorFields(e, r.error); });
  // Level 0 (the processed mesh) first; a level's number is its place.
  io.list("lods", r.lods, [&](auto& l, auto& lod, size_t level) {
    l.derived("level", [&] { return level; });
    l.count("triangles", lod.triangles);
    l.number("hausdorff_m", lod.hausdorff);
    l.number("hausdorff_rel", lod.hausdorffRel);
    l.number("seconds", lod.seconds);
    l.number("samples_per_face", lod.samplesPerFace);
  });
  io.number("seconds", r.seconds);
}

template <class R, class Fields>
Json write(const R& report, Fields fields) {
  Writer w;
  fields(w, report);
  return std::move(w.out);
}

template <class R, class Fields>
bool read(JsonReader& jr, const Json& json, const std::string& path, R& out, Fields fields) {
  if (!jr.object(json, path)) return false;
  Reader r(jr, json, path);
  fields(r, out);
  return r.ok();
}

}  // namespace

Json toJson(const ImportReport& r) {
  return write(r, [](auto& io, auto& x) { importFields(io, x); });
}
Json toJson(const CleanReport& r) {
  return write(r, [](auto& io, auto& x) { cleanFields(io, x); });
}
Json toJson(const DecimateReport& r) {
  return write(r, [](auto& io, auto& x) { decimateFields(io, x); });
}
Json toJson(const ErrorReport& r) {
  return write(r, [](auto& io, auto& x) { errorFields(io, x); });
}
Json toJson(const ProcessReport& r) {
  return write(r, [](auto& io, auto& x) { processFields(io, x); });
}

bool fromJson(JsonReader& reader, const Json& json, const std::string& path, ImportReport& out) {
  return read(reader, json, path, out, [](auto& io, auto& x) { importFields(io, x); });
}
bool fromJson(JsonReader& reader, const Json& json, const std::string& path, ProcessReport& out) {
  return read(reader, json, path, out, [](auto& io, auto& x) { processFields(io, x); });
}

}  // namespace hs::mesh
