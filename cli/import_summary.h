#pragma once
// What `hybridscape-cli import` prints after the import line: the processing
// report section by section, each row as its JSON field name, its value with
// unit, and what it means (scene/mesh_report_text.h), so the printed summary
// and the --report file name the same fields.
#include <string>

namespace hs::cli {

void printProcessReport(const std::string& processReportJson);

}  // namespace hs::cli
