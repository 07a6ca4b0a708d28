#pragma once
// What the passes of one frame share while the frame graph is built: the
// renderer's resources, the frame's world and visible set, its options and
// the statistics the passes add to. Include only inside render/.
#include <string>

#include "render/draw_source.h"
#include "render/frame_graph.h"
#include "render/render_resources.h"
#include "render/render_world.h"
#include "render/renderer.h"
#include "render/visible_set.h"

namespace hs::render {

struct FrameContext {
  RenderResources& res;
  const RenderWorld& world;
  const VisibleSet& visible;
  const scene::SceneSettings& settings;
  const RenderOptions& options;
  const RenderView& lodView;  // chooses every level of detail of the frame
  FrameStats& stats;
  // The sun's cascaded shadow maps of this frame (passes/shadow_passes.h);
  // invalid when nothing casts.
  TextureRef sunShadowMap{};
  // Spot and point lights' shadow maps and their data (passes/
  // local_shadow_pass.h); invalid when no such light casts in view. `views`
  // are every view of the frame (a light beyond its range from all of them
  // gets no map).
  TextureRef localShadowMaps{};
  BufferRef localShadowData{};
  const std::vector<RenderView>* views = nullptr;
  // The clustered light list (passes/light_culling.h): the point and spot
  // lights that reach a view, and the grid when the frame has one.
  size_t lightsInView = 0;
  BufferRef lightGrid{}, lightIndices{};
  // The kinds of geometry the frame draws (draw_source.h), in drawing
  // order, and its shadow views (each shadow map layer's volume, relative
  // to the frame origin), which every source culled once.
  std::vector<DrawSource*> sources{};
  std::vector<Frustum> shadowViews{};
  // A stereo pair's first eye, for the stylised effects whose pattern the
  // second eye takes from it by depth (so both eyes see the same pattern
  // on a surface): its single-sample depth and view, stippling's final
  // dots (passes/stipple_passes.h) and error diffusion's output
  // (passes/stylised_passes.h).
  struct FirstEye {
    TextureRef depth{};
    const RenderView* view = nullptr;
    BufferRef stippleSites{};
    uint32_t stippleCount = 0;
    TextureRef dithered{};
  };
  FirstEye firstEye{};
};

// One view of the frame: its camera, its index in the view block buffer,
// the caller's framebuffer it ends in, and the suffix its passes' and
// resources' names carry ("[left]"; empty for a mono frame).
struct ViewContext {
  const RenderView& view;
  size_t index = 0;
  unsigned target = 0;
  std::string suffix;
  std::string named(const std::string& what) const { return what + suffix; }
};

// Which eye of a stereo pair `v` is (0 or 1), given its single-sample
// `depth` in a frame of two views; -1 for any other view. The first eye
// records its depth and view in frame.firstEye for the second.
inline int stereoEye(FrameContext& frame, const ViewContext& v, TextureRef depth) {
  if (!depth.valid() || !frame.views || frame.views->size() != 2) return -1;
  if (v.index == 0) {
    frame.firstEye.depth = depth;
    frame.firstEye.view = &v.view;
  }
  return int(v.index);
}

}  // namespace hs::render
