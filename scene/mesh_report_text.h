#pragma once
// A mesh asset's processing report (MeshAsset::processReportJson, made by
// scene::importMeshFiles) as rows of text: what `hybridscape-cli import`
// prints, what the editor's error report dialog shows and the one line the
// Messages panel gets. Read from the stored JSON, so a report reopened from
// a saved scene reads the same as the one just made. Each row carries its
// JSON field name, which the CLI prints (hausdorff_m, p95_m, ...).
#include <string>
#include <vector>

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

// Empty when the text is not a processing report.
std::vector<ReportSection> processReportSections(const std::string& processReportJson);

// One line: "decimated 69,451 -> 6,945 triangles, hausdorff_m 0.00031 (0.12% of
// the diagonal), mean_m ..., 3 LODs, 0.4 s"; empty for an empty report.
std::string processReportSummary(const std::string& processReportJson);

}  // namespace hs::scene
