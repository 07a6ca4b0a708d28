#pragma once
// Combining view groups (Renderer::renderGroups): view i of every group of
// a frame, weighted and summed in linear HDR ("group_combine", RGBA16F),
// before the tone map (a cross-fade between two shots: weights 1 - a and
// a), or two of them by a stylised transition's pattern
// (shaders/group_combine.frag). Up to kMaxCombinedGroups images. Include
// only inside render/.
#include <utility>
#include <vector>

#include "render/frame_context.h"
#include "sequencer/camera_cuts.h"

namespace hs::render {

constexpr size_t kMaxCombinedGroups = 4;

// A patterned transition (sequencer::isPatterned) between images 0 and 1.
struct CombinePattern {
  sequencer::Transition transition = sequencer::Transition::Crossfade;  // not patterned: weights
  float progress = 0.0f;
  int64_t frame = 0;
};

// `images`: (HDR image, weight); returns the combined image.
TextureRef addGroupCombinePass(FrameGraph& graph, FrameContext& frame, const ViewContext& v,
                               const std::vector<std::pair<TextureRef, float>>& images,
                               const CombinePattern& pattern = {});

}  // namespace hs::render
