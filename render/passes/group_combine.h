#pragma once
// Combining view groups (Renderer::renderGroups): view i of every group of
// a frame, weighted and summed in linear HDR ("group_combine", RGBA16F),
// before the tone map (a cross-fade between two shots: weights 1 - a and
// a). Up to kMaxCombinedGroups images. Include only inside render/.
#include <utility>
#include <vector>

#include "render/frame_context.h"

namespace hs::render {

constexpr size_t kMaxCombinedGroups = 4;

// `images`: (HDR image, weight); returns the combined image.
TextureRef addGroupCombinePass(FrameGraph& graph, FrameContext& frame, const ViewContext& v,
                               const std::vector<std::pair<TextureRef, float>>& images);

}  // namespace hs::render
