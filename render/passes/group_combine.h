#pragma once
// Combining view groups (Renderer::renderGroups): view i of every group of
// a frame, weighted and summed in linear HDR ("group_combine", RGBA16F),
// before the tone map (a cross-fade between two shots: weights 1 - a and
// a), or two of them by a stylised transition's pattern
// (shaders/group_combine.frag). Up to kMaxCombinedGroups images. Include
// only inside render/.
#include <string>
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

// `images`: (HDR image, weight); returns the combined image. With
// `toTarget`, the images are finished pictures (each group's own post
// chain: cameras that override post settings differently) and the result
// is drawn into the view's framebuffer as it is ("picture_combine").
TextureRef addGroupCombinePass(FrameGraph& graph, FrameContext& frame, const ViewContext& v,
                               const std::vector<std::pair<TextureRef, float>>& images,
                               const CombinePattern& pattern = {}, bool toTarget = false);

// A copy of what framebuffer `fbo` holds (a group's finished picture, at
// the view's size) as a texture `name` (pass "<name>_copy") the combine
// can sample (RGBA16: 16-bit exports lose nothing).
TextureRef addTargetCopyPass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, unsigned fbo,
                             const std::string& name);

}  // namespace hs::render
