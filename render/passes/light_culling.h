#pragma once
// The clustered light list (docs/rendering.md, "Lights and exposure"):
// a compute pass, `light_culling`, bins the frame's point and spot lights
// into each view's froxels (shaders/light_clusters.glsl), and the passes
// that light surfaces loop over their pixel's cluster only.
//
// Once per frame, for every view: the pass is added before the views and
// runs one dispatch per view (its own froxels: a pixel finds its cluster
// from gl_FragCoord and its depth, exact for the eyes' off-axis
// projections); the light data itself is shared. A frame with no point or
// spot light whose range reaches a view's frustum adds no pass, creates no
// grid and compiles no clustered variant (LIGHTS_CLUSTERED). Include only
// inside render/.
#include <string>
#include <vector>

#include "render/frame_context.h"

namespace hs::render {

// Must match shaders/light_clusters.glsl.
inline constexpr int kLightTilesX = 16;
inline constexpr int kLightTilesY = 9;
inline constexpr int kLightSlices = 24;
inline constexpr int kLightClusterCap = 128;  // lights per cluster; more are dropped and counted
inline constexpr int kLightClusters = kLightTilesX * kLightTilesY * kLightSlices;
// Binding points (shaders/light_clusters.glsl; frame_blocks.h reserves 7).
inline constexpr unsigned kLightIndexBinding = 9;
inline constexpr unsigned kLightCullStatsBinding = 10;

// The point and spot lights whose range sphere meets at least one view's
// frustum (the others cannot light a visible pixel).
size_t pointLightsInView(const RenderWorld& world, const std::vector<RenderView>& views);

// Adds the light_culling pass when frame.lightsInView > 0 and the options
// do not ask for the brute-force loop; sets frame.lightGrid.
void addLightCullingPass(FrameGraph& graph, FrameContext& frame, const std::vector<ViewContext>& views);

// The defines of the surface shaders this frame: its fog (fog_block.h) and
// LIGHTS_CLUSTERED when the frame has a light grid.
std::vector<std::string> surfaceDefines(const FrameContext& frame);

// For the passes that light surfaces: declare the grid's read in setup,
// bind view `view`'s part of it in execute (nothing without a grid).
void readLightGrid(PassBuilder& b, const FrameContext& frame);
void bindLightGrid(const FrameContext& frame, const PassResources& r, size_t view);

}  // namespace hs::render
