#pragma once
#include <string>

#include <QJsonObject>

#include "mesh/mesh_import.h"

namespace hs::scene {

// The import report as JSON with plainly named fields (stored with the asset
// and printed by `hybridscape-cli import --report`).
QJsonObject importReportToJsonObject(const mesh::ImportReport& report);
std::string importReportToJson(const mesh::ImportReport& report);

}  // namespace hs::scene
