#pragma once
// The import and processing reports as JSON (hs::Json, core/json.h), with
// plain field names and units in the name (hausdorff_m, hausdorff_rel =
// fraction of the bounding-box diagonal, seconds), for `hybridscape-cli
// import --report`, the .hscene description and tools that read them
// (docs/meshes.md lists the fields).
//
// Each report's members are declared once (report_json.cpp), and both the
// writer and the reader follow that declaration, so they cannot disagree
// on a key. Numbers are written in the shortest form that reads back to the
// same double; a value that is not finite is written as null and read back
// as NaN. Members that are derived from others (hausdorff_rel, mean_rel,
// area_change_rel, ...) are written for people and tools and recomputed,
// not read. So write, read, write gives the same bytes.
//
// Reading is lenient about what is absent (a file written by an older
// build keeps the default) and strict about what is there: a member of the
// wrong type fails with its JSON path ("process_report.error.hausdorff_m:
// expected a number, not a string").
#include <string>

#include "core/json.h"
#include "mesh/mesh_import.h"
#include "meshproc/decimate.h"
#include "meshproc/error_metrics.h"
#include "meshproc/mesh_clean.h"
#include "meshproc/mesh_process.h"

namespace hs::mesh {

// {"file", "reader", "vertices_in", ..., "skipped_primitives", ...,
//  "geo_offset"?: {"offset_m", "source", "crs"}, "warnings", "seconds"}.
// "skipped_lines", the name this library's writer used before, is read too.
Json toJson(const ImportReport& report);
Json toJson(const CleanReport& report);
Json toJson(const DecimateReport& report);
Json toJson(const ErrorReport& report);
// {"cleaning": {...} | null, "decimation": {...} | null, "decimation_passes"
// (after a decimation), "error": {...} | null, "lods": [...], "seconds"}.
Json toJson(const ProcessReport& report);

// The object at `path` into `out` (which starts from its defaults).
bool fromJson(JsonReader& reader, const Json& json, const std::string& path, ImportReport& out);
bool fromJson(JsonReader& reader, const Json& json, const std::string& path, ProcessReport& out);

}  // namespace hs::mesh
