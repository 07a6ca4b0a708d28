#include "cli/import_summary.h"

#include <cstdio>

#include "scene/mesh_report_text.h"

namespace hs::cli {

void printProcessReport(const Json& processReport) {
  for (const scene::ReportSection& s : scene::processReportSections(processReport)) {
    std::printf("%s:\n", s.title.c_str());
    for (const scene::ReportRow& r : s.rows)
      std::printf("  %-30s %-28s %s\n", r.key.c_str(), r.value.c_str(), r.label.c_str());
  }
}

}  // namespace hs::cli
