#include "render/output_target.h"

#include <epoxy/gl.h>

namespace hs::render {

void OutputTarget::ensure(int width, int height, unsigned format) {
  if (format == 0) format = GL_RGBA8;
  if (fbo_ && width == width_ && height == height_ && format == format_) return;
  release();
  glCreateRenderbuffers(1, &color_);
  glNamedRenderbufferStorage(color_, format, width, height);
  glCreateFramebuffers(1, &fbo_);
  glNamedFramebufferRenderbuffer(fbo_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
  width_ = width;
  height_ = height;
  format_ = format;
}

void OutputTarget::release() {
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (color_) glDeleteRenderbuffers(1, &color_);
  fbo_ = color_ = format_ = 0;
  width_ = height_ = 0;
}

}  // namespace hs::render
