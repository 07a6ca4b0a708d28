#pragma once
// Shadow passes (docs/rendering.md "Shadows"): the sun's cascaded shadow
// maps and the spot and point lights' maps (local_shadow_pass.h), drawn
// once per frame before any view's passes and read by every view (both
// eyes of a stereo pair sample the same maps). Without a casting sun
// (settings.shadows and the sun's casts_shadows), no sun pass is added and
// nothing is allocated: the maps and the caster data are the frame graph's
// transient resources, so they exist only in frames that draw them.
// Include only inside render/.
#include "render/frame_context.h"

namespace hs::render {

// Resolves the settings, computes the sun's cascades (shadow_cascades.h),
// uploads the frame's ShadowBlock (cascade count 0 when there are none) and
// adds the sun's shadow pass if the frame casts, and the spot and point
// lights' pass. Sets frame.sunShadowMap (and the local maps).
void addShadowPasses(FrameGraph& graph, FrameContext& frame);

// For the passes that light surfaces (opaque meshes, terrain): declare the
// read of the frame's shadow maps in setup, bind them in execute.
void readShadowMaps(PassBuilder& b, const FrameContext& frame);
void bindShadowMaps(const FrameContext& frame, const PassResources& r);

}  // namespace hs::render
