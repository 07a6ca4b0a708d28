#pragma once
// The terrain operations the editor and `hybridscape-cli terrain` share,
// declared once (core/params.h): what each takes, with ranges, units,
// defaults and help. Their parameters are the domain structs'
// declarations (erosion, DEM import, heightmap export) plus what picks the
// terrain and the scene. `terrain new` is scene/terrain_ops.h's (it fills
// scene::ops::NewTerrain).
#include "core/params.h"

namespace hs::terrain {

// `terrain erode`: thermal or hydraulic erosion over a terrain (or where a
// paint layer is painted). `iterations` is one option for both solvers
// (their declarations share its range; the default is the solver's).
const OperationDecl& terrainErodeOperation();
// `terrain import`: a DEM as a new terrain, or into an existing one.
const OperationDecl& terrainImportOperation();
// `terrain export`: heights as an image or RAW file, and paint weights.
const OperationDecl& terrainExportOperation();
// `terrain paint-rules`: paint layers by altitude and slope.
const OperationDecl& terrainPaintRulesOperation();
// `terrain layer`: a paint layer's material (name, albedo and its texture,
// normal map, roughness, tiling). The editor's Layers editor takes its
// ranges from here.
const OperationDecl& terrainLayerOperation();

}  // namespace hs::terrain
