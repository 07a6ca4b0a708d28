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
#include "render/shadow_cascades.h"

namespace hs::render {

// What planShadows decided, for addShadowPasses.
struct ShadowPlan {
  ShadowConfig config;
  size_t sunFirstView = 0;    // the cascades' shadow views (FrameContext::shadowViews)
  size_t localFirstView = 0;  // the spot and point lights' layers'
  size_t localLayers = 0;
  int localLayerSize = 0;
};

// Resolves the settings, computes the sun's cascades (shadow_cascades.h)
// and the spot and point lights' maps (local_shadow_pass.h), uploads the
// frame's ShadowBlock (cascade count 0 when there are none) and adds their
// shadow views, so every draw source culls its casters once, before the
// sources prepare their draws (draw_source.h).
ShadowPlan planShadows(FrameContext& frame);
// Adds the spot and point lights' pass and the sun's pass, each only if
// something casts. Sets frame.sunShadowMap (and the local maps).
void addShadowPasses(FrameGraph& graph, FrameContext& frame, const ShadowPlan& plan);

// For the passes that light surfaces (opaque meshes, terrain): declare the
// read of the frame's shadow maps in setup, bind them in execute.
void readShadowMaps(PassBuilder& b, const FrameContext& frame);
void bindShadowMaps(const FrameContext& frame, const PassResources& r);

}  // namespace hs::render
