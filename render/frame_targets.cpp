#include "render/frame_targets.h"

namespace hs::render {
namespace {

GLuint texture2D(GLenum format, int w, int h) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, format, w, h);
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

GLuint renderbuffer(GLenum format, int w, int h, int samples) {
  GLuint r = 0;
  glCreateRenderbuffers(1, &r);
  if (samples > 1)
    glNamedRenderbufferStorageMultisample(r, samples, format, w, h);
  else
    glNamedRenderbufferStorage(r, format, w, h);
  return r;
}

void deleteFbo(GLuint& fbo) {
  if (fbo) glDeleteFramebuffers(1, &fbo);
  fbo = 0;
}
void deleteTex(GLuint& t) {
  if (t) glDeleteTextures(1, &t);
  t = 0;
}
void deleteRb(GLuint& r) {
  if (r) glDeleteRenderbuffers(1, &r);
  r = 0;
}

}  // namespace

void FrameTargets::ensure(int width, int height, int samples, bool fxaa) {
  if (width == width_ && height == height_ && samples == samples_ && fxaa == fxaa_ && hdrFbo_) return;
  releaseMain();
  width_ = width;
  height_ = height;
  samples_ = samples;
  fxaa_ = fxaa;
  // Linear HDR colour: RGBA16F; 32-bit float depth for reversed Z.
  hdrColor_ = texture2D(GL_RGBA16F, width, height);
  glCreateFramebuffers(1, &hdrFbo_);
  glNamedFramebufferTexture(hdrFbo_, GL_COLOR_ATTACHMENT0, hdrColor_, 0);
  if (samples > 1) {
    msaaColor_ = renderbuffer(GL_RGBA16F, width, height, samples);
    msaaDepth_ = renderbuffer(GL_DEPTH_COMPONENT32F, width, height, samples);
    glCreateFramebuffers(1, &msaaFbo_);
    glNamedFramebufferRenderbuffer(msaaFbo_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaaColor_);
    glNamedFramebufferRenderbuffer(msaaFbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaaDepth_);
  } else {
    hdrDepth_ = renderbuffer(GL_DEPTH_COMPONENT32F, width, height, 1);
    glNamedFramebufferRenderbuffer(hdrFbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, hdrDepth_);
  }
  if (fxaa) {
    ldrColor_ = texture2D(GL_RGBA8, width, height);
    glCreateFramebuffers(1, &ldrFbo_);
    glNamedFramebufferTexture(ldrFbo_, GL_COLOR_ATTACHMENT0, ldrColor_, 0);
  }
}

void FrameTargets::ensurePick() {
  if (pickFbo_) return;
  pickColor_ = renderbuffer(GL_R32UI, 1, 1, 1);
  pickDepth_ = renderbuffer(GL_DEPTH_COMPONENT32F, 1, 1, 1);
  glCreateFramebuffers(1, &pickFbo_);
  glNamedFramebufferRenderbuffer(pickFbo_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, pickColor_);
  glNamedFramebufferRenderbuffer(pickFbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, pickDepth_);
}

GLuint FrameTargets::resolve() {
  if (samples_ > 1)
    glBlitNamedFramebuffer(msaaFbo_, hdrFbo_, 0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                           GL_NEAREST);
  return hdrColor_;
}

GLuint FrameTargets::depthReadFbo() {
  if (samples_ <= 1) return hdrFbo_;
  if (!depthResolveFbo_) {
    depthResolve_ = renderbuffer(GL_DEPTH_COMPONENT32F, width_, height_, 1);
    glCreateFramebuffers(1, &depthResolveFbo_);
    glNamedFramebufferRenderbuffer(depthResolveFbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthResolve_);
  }
  // Depth is not averaged: one sample per pixel, which is what a parallax
  // extreme should come from (an averaged edge depth belongs to no surface).
  glBlitNamedFramebuffer(msaaFbo_, depthResolveFbo_, 0, 0, width_, height_, 0, 0, width_, height_,
                         GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  return depthResolveFbo_;
}

size_t FrameTargets::gpuBytes() const {
  const size_t px = size_t(width_) * size_t(height_);
  size_t n = hdrFbo_ ? px * 8 : 0;                       // RGBA16F resolve/scene colour
  if (samples_ > 1) n += px * size_t(samples_) * (8 + 4);  // MSAA colour + depth
  else if (hdrDepth_) n += px * 4;
  if (depthResolve_) n += px * 4;
  if (ldrFbo_) n += px * 4;
  return n;
}

void FrameTargets::releaseMain() {
  deleteFbo(msaaFbo_);
  deleteRb(msaaColor_);
  deleteRb(msaaDepth_);
  deleteFbo(hdrFbo_);
  deleteTex(hdrColor_);
  deleteRb(hdrDepth_);
  deleteFbo(ldrFbo_);
  deleteTex(ldrColor_);
  deleteFbo(depthResolveFbo_);
  deleteRb(depthResolve_);
  width_ = height_ = samples_ = 0;
}

void FrameTargets::release() {
  releaseMain();
  deleteFbo(pickFbo_);
  deleteRb(pickColor_);
  deleteRb(pickDepth_);
}

}  // namespace hs::render
