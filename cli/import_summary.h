#pragma once
// What `hybridscape-cli import` prints after the import line: the processing
// report section by section, each row as its JSON field name, its value with
// unit, and what it means (scene/mesh_report_text.h), so the printed summary
// and the --report file name the same fields.
#include "core/json.h"

namespace hs::cli {

// `processReport`: scene::ImportedMesh::processReport (null prints nothing).
void printProcessReport(const Json& processReport);

}  // namespace hs::cli
