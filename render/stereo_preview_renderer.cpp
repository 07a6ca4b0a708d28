#include "render/stereo_preview_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

#include <epoxy/gl.h>

#include "sequencer/stereo_layout.h"

namespace hs::render {

namespace {

// A picture of the eye's pixels (GL rows bottom-up, kept as they are: the
// anaglyph is per pixel, and the texture goes back to GL).
hs::Image readEye(unsigned fbo, int w, int h) {
  hs::Image img = hs::Image::make8(w, h);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba8.data());
  return img;
}

std::vector<float> readDepth(Renderer& r, int w, int h, size_t view) {
  std::vector<float> d(size_t(w) * size_t(h));
  r.readDepth(d.data(), view);
  // Rows bottom-up; the comfort check of off-axis and parallel rigs only
  // needs the depth range, toe-in reprojects pixels: flip to top-down.
  flipRows(d.data(), size_t(w) * sizeof(float), size_t(h));
  return d;
}

void blit(unsigned from, int w, int h, unsigned to, const FitRect& r) {
  glBlitNamedFramebuffer(from, to, 0, 0, w, h, r.x, r.y, r.x + r.width, r.y + r.height, GL_COLOR_BUFFER_BIT,
                         (w == r.width && h == r.height) ? GL_NEAREST : GL_LINEAR);
}

}  // namespace

FitRect fitAspect(double aspect, int width, int height) {
  FitRect r;
  if (width <= 0 || height <= 0 || !(aspect > 0.0)) return r;
  if (double(width) / double(height) > aspect) {
    r.height = height;
    r.width = std::max(1, int(std::lround(height * aspect)));
  } else {
    r.width = width;
    r.height = std::max(1, int(std::lround(width / aspect)));
  }
  r.x = (width - r.width) / 2;
  r.y = (height - r.height) / 2;
  return r;
}

void StereoPreviewRenderer::ensureEyes(int w, int h) {
  for (Eye& e : eyes_) e.target.ensure(w, h);
  width_ = w;
  height_ = h;
}

void StereoPreviewRenderer::ensureAnaglyph(int w, int h) {
  if (anaglyphFbo_ && w == anaglyphWidth_ && h == anaglyphHeight_) return;
  if (anaglyphFbo_) glDeleteFramebuffers(1, &anaglyphFbo_);
  if (anaglyphTexture_) glDeleteTextures(1, &anaglyphTexture_);
  glCreateTextures(GL_TEXTURE_2D, 1, &anaglyphTexture_);
  glTextureStorage2D(anaglyphTexture_, 1, GL_RGBA8, w, h);
  glCreateFramebuffers(1, &anaglyphFbo_);
  glNamedFramebufferTexture(anaglyphFbo_, GL_COLOR_ATTACHMENT0, anaglyphTexture_, 0);
  anaglyphWidth_ = w;
  anaglyphHeight_ = h;
}

StereoPreviewResult StereoPreviewRenderer::draw(Renderer& renderer, const scene::SceneState& state,
                                                scene::EntityId camera, StereoPreviewMode mode, double outputAspect,
                                                unsigned targetFbo, int targetWidth, int targetHeight,
                                                const sequencer::ComfortOptions* comfort,
                                                const PreviewTransition* transition) {
  StereoPreviewResult result;
  if (!renderer.initialized() || targetWidth <= 0 || targetHeight <= 0) return result;
  // Side by side shows two eyes of the output aspect next to each other.
  const bool sbs = mode == StereoPreviewMode::SideBySide;
  const FitRect area = fitAspect(outputAspect * (sbs ? 2.0 : 1.0), targetWidth, targetHeight);
  const int eyeW = sbs ? std::max(1, area.width / 2) : area.width, eyeH = area.height;
  if (eyeW <= 0 || eyeH <= 0) return result;
  ensureEyes(eyeW, eyeH);
  const EyeViews views = eyeViews(state, camera, eyeW, eyeH);

  const bool needLeft = mode != StereoPreviewMode::Right || comfort;
  const bool needRight = mode != StereoPreviewMode::Left || (comfort && views.eyes.mode == sequencer::StereoMode::ToeIn);
  std::vector<float> depth[2];
  RenderOptions options;
  options.showGrid = true;
  options.lodView = &views.mono;  // both eyes draw the same mesh levels (renderer.h)
  options.streamClusters = true;  // interactive: cluster pages arrive over the next frames
  options.keepDepth = comfort != nullptr;
  // The eyes the mode shows, in one frame (what does not depend on the eye
  // is done once).
  std::vector<ViewTarget> targets;
  if (needLeft) targets.push_back({views.left, eyes_[0].target.fbo(), "left"});
  if (needRight) targets.push_back({views.right, eyes_[1].target.fbo(), "right"});
  size_t depthBase = 0;                 // the first view whose depth the comfort check reads
  const EyeViews* checked = &views;     // and whose eyes it checks
  std::optional<EyeViews> incoming;
  if (transition && transition->incoming != scene::kNoEntity && state.find(transition->incoming)) {
    // Both shots as two view groups, combined into the eyes' targets as an
    // export combines them (render/stereo_frame_source.cpp).
    incoming = eyeViews(state, transition->incoming, eyeW, eyeH);
    const EyeViews& in = *incoming;
    std::vector<ViewGroup> groups(2);
    GroupCombine combine = combineOf(transition->shot, transition->frame);
    for (size_t i = 0; i < targets.size(); ++i) {
      const bool left = targets[i].fbo == eyes_[0].target.fbo();
      Eye& eye = eyes_[left ? 0 : 1];
      for (OutputTarget& g : eye.groups) g.ensure(eyeW, eyeH);
      groups[0].targets.push_back({targets[i].view, eye.groups[0].fbo(), targets[i].name});
      groups[1].targets.push_back({left ? in.left : in.right, eye.groups[1].fbo(), targets[i].name});
      combine.targets.push_back({left ? in.left : in.right, targets[i].fbo, targets[i].name});
    }
    groups[0].lodView = &views.mono;
    groups[1].lodView = &in.mono;
    const std::vector<FrameStats> stats = renderer.renderGroups(state, groups, options, &combine);
    if (!stats.empty()) result.stats = stats.back();
    if (combine.weights[1] > combine.weights[0]) depthBase = targets.size(), checked = &in;
  } else {
    result.stats = renderer.renderViews(state, targets, options);
  }
  if (comfort && needLeft) {
    depth[0] = readDepth(renderer, eyeW, eyeH, depthBase);
    if (needRight && checked->eyes.mode == sequencer::StereoMode::ToeIn && targets.size() > 1)
      depth[1] = readDepth(renderer, eyeW, eyeH, depthBase + 1);
  }
  if (comfort && !depth[0].empty()) {
    auto image = [&](const std::vector<float>& d, const sequencer::CameraModel& c) {
      return sequencer::DepthImage{eyeW, eyeH, d.data(), sequencer::DepthKind::ReversedZ, c.nearClip, c.farClip};
    };
    const sequencer::DepthImage l = image(depth[0], checked->eyes.left), r = image(depth[1], checked->eyes.right);
    result.comfort = sequencer::checkComfort(checked->eyes, l, depth[1].empty() ? nullptr : &r, *comfort);
  }

  // Letterbox bars, then the picture.
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, targetFbo);
  glViewport(0, 0, targetWidth, targetHeight);
  glDisable(GL_SCISSOR_TEST);
  const float bars[4] = {0.09f, 0.09f, 0.1f, 1.0f};
  glClearNamedFramebufferfv(targetFbo, GL_COLOR, 0, bars);
  switch (mode) {
    case StereoPreviewMode::Left: blit(eyes_[0].target.fbo(), eyeW, eyeH, targetFbo, area); break;
    case StereoPreviewMode::Right: blit(eyes_[1].target.fbo(), eyeW, eyeH, targetFbo, area); break;
    case StereoPreviewMode::SideBySide: {
      FitRect l = area, r = area;
      l.width = r.width = eyeW;
      r.x = area.x + eyeW;
      blit(eyes_[0].target.fbo(), eyeW, eyeH, targetFbo, l);
      blit(eyes_[1].target.fbo(), eyeW, eyeH, targetFbo, r);
      break;
    }
    case StereoPreviewMode::Anaglyph: {
      // The export's composition on the CPU: the preview shows the film's colours.
      const hs::Image l = readEye(eyes_[0].target.fbo(), eyeW, eyeH), r = readEye(eyes_[1].target.fbo(), eyeW, eyeH);
      const std::vector<hs::Image> out = sequencer::composeLayout(sequencer::StereoLayout::Anaglyph, l, r);
      if (out.empty()) break;
      ensureAnaglyph(eyeW, eyeH);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
      glTextureSubImage2D(anaglyphTexture_, 0, 0, 0, eyeW, eyeH, GL_RGBA, GL_UNSIGNED_BYTE, out.front().rgba8.data());
      blit(anaglyphFbo_, eyeW, eyeH, targetFbo, area);
      break;
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);
  result.drawn = true;
  result.eyeWidth = eyeW;
  result.eyeHeight = eyeH;
  return result;
}

void StereoPreviewRenderer::release() {
  for (Eye& e : eyes_) {
    e.target.release();
    for (OutputTarget& g : e.groups) g.release();
  }
  if (anaglyphFbo_) glDeleteFramebuffers(1, &anaglyphFbo_);
  if (anaglyphTexture_) glDeleteTextures(1, &anaglyphTexture_);
  anaglyphFbo_ = anaglyphTexture_ = 0;
  width_ = height_ = anaglyphWidth_ = anaglyphHeight_ = 0;
}

}  // namespace hs::render
