#pragma once
// The off-screen buffers a frame renders through, allocated for what the
// frame needs only: the multisampled scene buffer exists only with MSAA, the
// LDR buffer only with FXAA, the pick buffer only once something is picked.
#include <epoxy/gl.h>

namespace hs::render {

class FrameTargets {
 public:
  // No GL in the destructor: the context may already be gone. Call release().
  // (Re)creates buffers when size, sample count or FXAA use changes.
  void ensure(int width, int height, int samples, bool fxaa);
  void ensurePick();
  void release();

  GLuint sceneFbo() const { return samples_ > 1 ? msaaFbo_ : hdrFbo_; }
  // Resolves MSAA into the single-sample HDR texture (no-op without MSAA) and returns it.
  GLuint resolve();
  GLuint resolvedTexture() const { return hdrColor_; }
  GLuint ldrFbo() const { return ldrFbo_; }
  GLuint ldrTexture() const { return ldrColor_; }
  GLuint pickFbo() const { return pickFbo_; }
  // A single-sample framebuffer holding the last frame's depth: the scene
  // buffer itself, or with MSAA a resolve target made on first use (only
  // frames whose depth is read need it).
  GLuint depthReadFbo();
  int width() const { return width_; }
  int height() const { return height_; }
  size_t gpuBytes() const;

 private:
  void releaseMain();
  int width_ = 0, height_ = 0, samples_ = 0;
  bool fxaa_ = false;
  GLuint msaaFbo_ = 0, msaaColor_ = 0, msaaDepth_ = 0;
  GLuint hdrFbo_ = 0, hdrColor_ = 0, hdrDepth_ = 0;
  GLuint ldrFbo_ = 0, ldrColor_ = 0;
  GLuint pickFbo_ = 0, pickColor_ = 0, pickDepth_ = 0;
  GLuint depthResolveFbo_ = 0, depthResolve_ = 0;
};

}  // namespace hs::render
