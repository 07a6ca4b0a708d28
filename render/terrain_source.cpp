#include "render/terrain_source.h"

#include "render/frame_context.h"

namespace hs::render {

void TerrainSource::draw(FrameContext& frame, const DrawCall& call, const PassResources&) {
  if (world_.terrains.empty()) return;
  TerrainPass& terrain = frame.res.terrain;
  const scene::SceneState& state = *world_.state;
  switch (call.variant) {
    case DrawVariant::Surface: {
      // The layered depth of field's capture takes meshes alone (terrain
      // reaches it through the opaque image); terrains have no translucency.
      if (call.surfaces != SurfaceSet::Opaque) return;
      const TerrainFrameStats ts = terrain.draw(state, world_.terrains, (*frame.views)[call.view], frame.lodView,
                                                call.defines);
      frame.stats.trianglesDrawn += ts.triangles;
      frame.stats.drawCalls += ts.terrains;
      frame.stats.terrainTriangles += ts.triangles;
      frame.stats.terrainPatches += ts.patches;
      frame.stats.terrainUploadBytes += ts.upload.bytes;
      frame.stats.terrainUploadMs += ts.upload.cpuMs;
      break;
    }
    case DrawVariant::Depth:
      terrain.drawShadow(state, world_.terrains, frame.lodView, frame.shadowViews[call.shadowView]);
      break;
    case DrawVariant::Pick: terrain.drawPick(state, world_.terrains, frame.lodView, call.pickBase); break;
  }
}

}  // namespace hs::render
