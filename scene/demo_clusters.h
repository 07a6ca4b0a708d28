#pragma once
// The demo's huge-scan sample (docs/meshes.md "Cluster hierarchy",
// docs/rendering.md "Cluster hierarchies"): the Stanford bunny again, as a
// cluster hierarchy (one asset whose pages stream from the scene file),
// 60 times its size, standing apart 4 km east of the valley so no earlier
// camera sees it, with a "Scan Camera" close to its flank where the cut
// mixes levels (View > Cluster Levels shows them).
#include "mesh/mesh_data.h"
#include "scene/scene_state.h"

namespace hs::scene {

void addDemoClusterScan(SceneState& state, const mesh::MeshData& bunny);

}  // namespace hs::scene
