#pragma once
// The environment pass (render/environment_maps.h): once per frame, before
// the views, and only when the analytic sky's inputs changed since the maps
// were made. With the gradient sky it frees the maps. Include only inside
// render/.
#include "render/frame_context.h"

namespace hs::render {

void addEnvironmentPass(FrameGraph& graph, FrameContext& frame);

}  // namespace hs::render
