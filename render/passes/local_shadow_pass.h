#pragma once
// Spot and point light shadow maps (docs/rendering.md "Shadows", "Spot and
// point lights"; the numbers in local_shadows.h): one pass per frame,
// `shadow_local`, drawing every shadow-casting spot's map and every
// shadow-casting point light's six cube faces into the layers of one depth
// array texture (`local_shadow_maps`, texture unit 16), with the lookup data
// in a storage buffer (`local_shadow_data`, binding 11). Both eyes of a
// stereo pair read the same maps. A light casts when settings.shadows is on
// and its own casts_shadows is set, and only if its range reaches a view;
// with no such light no pass is added and nothing is allocated (transient
// resources of the frame graph). Include only inside render/.
#include "render/frame_blocks.h"
#include "render/frame_context.h"
#include "render/passes/shadow_passes.h"

namespace hs::render {

// Chooses the casting lights (frame.res.shadows.local), fills
// block.localParams (x = 0 when none) and adds their layers' shadow views
// (plan.localFirstView, localLayers, localLayerSize).
void planLocalShadows(FrameContext& frame, int maxTextureSize, ShadowBlock& block, ShadowPlan& plan);
// Adds the pass when a light casts; sets frame.localShadowMaps and
// frame.localShadowData.
void addLocalShadowPass(FrameGraph& graph, FrameContext& frame, const ShadowPlan& plan);

// For the passes that light surfaces: declare the reads, bind at draw time.
void readLocalShadowMaps(PassBuilder& b, const FrameContext& frame);
void bindLocalShadowMaps(const FrameContext& frame, const PassResources& r);

}  // namespace hs::render
