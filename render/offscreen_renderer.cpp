#include "render/offscreen_renderer.h"

#include <epoxy/gl.h>

#include "render/egl_context.h"
#include "render/output_target.h"

namespace hs::render {

struct OffscreenRenderer::Impl {
  EglContext egl;
  Renderer renderer;
  OutputTarget output;
  std::vector<std::unique_ptr<OutputTarget>> extraOutputs;  // views after the first (renderViewsOnly)

  ~Impl() {
    if (egl.makeCurrent()) {
      renderer.shutdown();
      output.release();
      for (auto& o : extraOutputs) o->release();
    }
  }
};

OffscreenRenderer::OffscreenRenderer() : d_(std::make_unique<Impl>()) {}
OffscreenRenderer::~OffscreenRenderer() = default;

bool OffscreenRenderer::initialize(std::string& error) {
  if (!d_->egl.create(error)) return false;
  glDescription_ = currentGlDescription();
  return d_->renderer.initialize(error);
}

const std::string& OffscreenRenderer::eglPlatform() const { return d_->egl.platform(); }
Renderer& OffscreenRenderer::renderer() { return d_->renderer; }
bool OffscreenRenderer::makeCurrent() { return d_->egl.makeCurrent(); }

Image OffscreenRenderer::render(const scene::SceneState& state, const RenderView& view, bool hdr,
                                FrameStats* stats, const RenderOptions& options) {
  d_->egl.makeCurrent();
  d_->output.ensure(view.width, view.height);
  RenderOptions o = options;
  o.keepHdr = hdr;
  const FrameStats s = d_->renderer.render(state, view, d_->output.fbo(), o);
  if (stats) *stats = s;
  return hdr ? d_->renderer.readHdr() : d_->renderer.readDisplay(d_->output.fbo(), view.width, view.height);
}

Image OffscreenRenderer::renderMix(const scene::SceneState& state, const std::vector<RenderView>& views,
                                   const std::vector<float>& weights, bool hdr, FrameStats* stats,
                                   const RenderOptions& options, const GroupCombine* pattern) {
  d_->egl.makeCurrent();
  if (views.empty()) return {};
  std::vector<ViewGroup> groups;
  for (size_t i = 0; i < views.size(); ++i) {
    while (d_->extraOutputs.size() <= i) d_->extraOutputs.push_back(std::make_unique<OutputTarget>());
    d_->extraOutputs[i]->ensure(views[i].width, views[i].height);
    groups.push_back({{ViewTarget{views[i], d_->extraOutputs[i]->fbo(), {}}}, nullptr});
  }
  d_->output.ensure(views[0].width, views[0].height);
  GroupCombine combine;
  if (pattern) combine = *pattern;
  combine.targets = {ViewTarget{views[0], d_->output.fbo(), {}}};
  combine.weights = weights;
  RenderOptions o = options;
  o.keepHdr = hdr;
  const std::vector<FrameStats> s = d_->renderer.renderGroups(state, groups, o, &combine);
  if (stats && !s.empty()) {
    // The frame's figures: the groups' draws summed, the last group's passes (with the mix).
    *stats = s.back();
    stats->passes.clear();
    for (size_t i = 0; i < s.size(); ++i) {
      if (i + 1 < s.size()) {
        stats->trianglesDrawn += s[i].trianglesDrawn;
        stats->drawCalls += s[i].drawCalls;
      }
      stats->passes.insert(stats->passes.end(), s[i].passes.begin(), s[i].passes.end());
    }
  }
  return hdr ? d_->renderer.readHdr(views.size())
             : d_->renderer.readDisplay(d_->output.fbo(), views[0].width, views[0].height);
}

FrameStats OffscreenRenderer::renderOnly(const scene::SceneState& state, const RenderView& view,
                                         const RenderOptions& options) {
  d_->egl.makeCurrent();
  d_->output.ensure(view.width, view.height);
  FrameStats s = d_->renderer.render(state, view, d_->output.fbo(), options);
  glFinish();
  return s;
}

FrameStats OffscreenRenderer::renderViewsOnly(const scene::SceneState& state, const std::vector<RenderView>& views,
                                              const RenderOptions& options) {
  d_->egl.makeCurrent();
  std::vector<ViewTarget> targets;
  static const char* const kNames[] = {"left", "right"};
  for (size_t i = 0; i < views.size(); ++i) {
    OutputTarget* out = &d_->output;
    if (i > 0) {
      while (d_->extraOutputs.size() < i) d_->extraOutputs.push_back(std::make_unique<OutputTarget>());
      out = d_->extraOutputs[i - 1].get();
    }
    out->ensure(views[i].width, views[i].height);
    const std::string name = views.size() == 1 ? "" : i < 2 ? kNames[i] : "view" + std::to_string(i);
    targets.push_back({views[i], out->fbo(), name});
  }
  FrameStats s = d_->renderer.renderViews(state, targets, options);
  glFinish();
  return s;
}

}  // namespace hs::render
