#pragma once
// Reports as JSON, with plain field names and units in the name
// (hausdorff_m, hausdorff_rel = fraction of the bounding-box diagonal,
// seconds), for `hybridscape-cli import --report` and for tools that read
// it. No dependency: the library has no Qt, and the format is small.
#include <string>

#include "mesh/mesh_import.h"
#include "meshproc/decimate.h"
#include "meshproc/error_metrics.h"
#include "meshproc/mesh_clean.h"
#include "meshproc/mesh_process.h"

namespace hs::mesh {

std::string toJson(const ImportReport& report);
std::string toJson(const CleanReport& report);
std::string toJson(const DecimateReport& report);
std::string toJson(const ErrorReport& report);
// The whole import: {"import": ..., "cleaning": ..., "decimation": ...,
// "error": ..., "lods": [...], "seconds": ...}; `import` may be null.
std::string processReportJson(const ProcessReport& report, const ImportReport* import = nullptr);

}  // namespace hs::mesh
