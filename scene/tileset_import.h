#pragma once
// `import tileset.json SCENE` (issue 38 item 5): an OGC 3D Tiles tileset
// (mesh/tileset_reader.h) comes in as one asset with a cluster hierarchy
// made from its tile tree (meshproc/cluster_from_tiles.h), so scans
// processed elsewhere keep their levels of detail and stream from the
// scene file like a hierarchy built here.
//
// Placement: a tileset in ECEF (the usual case: its vertices lie near the
// Earth's surface, 6,300-6,400 km from its centre) is converted vertex by
// vertex through PROJ (terrain/gdal_door.h) to the UTM zone of its centre
// ("auto"; heights on the WGS 84 ellipsoid, no geoid), the frame a DEM
// imported with `terrain import --crs utm` has, so the two line up; or to
// any CRS named. A tileset in a local frame is taken as metres, z up.
// The asset's origin is the middle of its bounds in that CRS.
#include <string>

#include "core/progress.h"
#include "scene/import_pipeline.h"

namespace hs::scene {

ImportedMesh importTileset(const std::string& path, const MeshImportRequest& request,
                           const Progress* progress = nullptr);

// Whether a point `metres` from the Earth's centre is ECEF: the WGS 84
// ellipsoid lies between 6,356.8 km (poles) and 6,378.1 km (equator); the
// band 6,300-6,400 km takes the Dead Sea to well above the Himalaya.
inline bool nearEarthSurfaceEcef(double metres) { return metres > 6'300'000.0 && metres < 6'400'000.0; }

// The name an imported file's asset and entity get: the file's stem, or
// for a tileset (always tileset.json) the folder that holds it. The CLI's
// import and the editor's use it.
std::string importedMeshName(const std::string& path);

}  // namespace hs::scene
