#include "render/offscreen_renderer.h"

#include <epoxy/gl.h>

#include "render/egl_context.h"

namespace hs::render {

struct OffscreenRenderer::Impl {
  EglContext egl;
  Renderer renderer;
  GLuint fbo = 0, color = 0;
  int width = 0, height = 0;

  void ensureOutput(int w, int h) {
    if (w == width && h == height && fbo) return;
    if (fbo) glDeleteFramebuffers(1, &fbo);
    if (color) glDeleteRenderbuffers(1, &color);
    glCreateRenderbuffers(1, &color);
    glNamedRenderbufferStorage(color, GL_RGBA8, w, h);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferRenderbuffer(fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
    width = w;
    height = h;
  }
  ~Impl() {
    if (egl.makeCurrent()) {
      renderer.shutdown();
      if (fbo) glDeleteFramebuffers(1, &fbo);
      if (color) glDeleteRenderbuffers(1, &color);
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
  d_->ensureOutput(view.width, view.height);
  RenderOptions o = options;
  o.keepHdr = hdr;
  const FrameStats s = d_->renderer.render(state, view, d_->fbo, o);
  if (stats) *stats = s;
  return hdr ? d_->renderer.readHdr() : d_->renderer.readDisplay(d_->fbo, view.width, view.height);
}

FrameStats OffscreenRenderer::renderOnly(const scene::SceneState& state, const RenderView& view,
                                         const RenderOptions& options) {
  d_->egl.makeCurrent();
  d_->ensureOutput(view.width, view.height);
  FrameStats s = d_->renderer.render(state, view, d_->fbo, options);
  glFinish();
  return s;
}

}  // namespace hs::render
