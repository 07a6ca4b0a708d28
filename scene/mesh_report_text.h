#pragma once
// A mesh asset's processing report (MeshAsset::processReport, made by
// scene::importMeshFiles) as rows of text: what `hybridscape-cli import`
// prints, what the editor's error report dialog shows and the one line the
// Messages panel gets. Read from the stored JSON through its reader
// (asset_reports.h), so a report reopened from a saved scene reads the same
// as the one just made. Each row carries its JSON field name, which the CLI
// prints (hausdorff_m, p95_m, ...).
#include <string>
#include <vector>

#include "core/json.h"

namespace hs::scene {

struct ReportRow {
  std::string key;    // JSON field name ("hausdorff_m"); empty for rows that combine several
  std::string label;  // plain words ("Hausdorff distance")
  std::string value;  // formatted with its unit ("0.000312 m")
};

struct ReportSection {
  std::string title;  // "Error", "Decimation", "Cleaning", "LODs", "Tiles"
  std::vector<ReportRow> rows;
};

// Empty when `processReport` is null or not a processing report.
std::vector<ReportSection> processReportSections(const Json& processReport);

// One line: "decimated 69,451 -> 6,945 triangles, hausdorff_m 0.00031 (0.12% of
// the diagonal), mean_m ..., 3 LODs, 0.4 s"; empty when there is no report.
std::string processReportSummary(const Json& processReport);

// What the processing could not do as asked, one line each (a maximum
// error no run met); the editor's Messages and the CLI's stderr show them.
std::vector<std::string> processWarnings(const Json& processReport);

}  // namespace hs::scene
