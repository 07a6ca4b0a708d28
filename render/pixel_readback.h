#pragma once
// Asynchronous readback through a pixel buffer object: reads queued into
// the buffer return at once, a fence marks the end of a frame's reads, and
// map() waits for that fence only when the pixels are wanted. With two of
// these the GPU renders frame N+1 while frame N's pixels travel (a frame
// in flight each). Include only inside render/.
#include <cstddef>
#include <cstdint>

#include <epoxy/gl.h>

namespace hs::render {

class PixelReadback {
 public:
  PixelReadback() = default;
  PixelReadback(const PixelReadback&) = delete;
  PixelReadback& operator=(const PixelReadback&) = delete;
  // No GL here: the context may be gone. Call release() while it is current.
  ~PixelReadback() = default;

  // Makes the buffer at least `bytes` long (contents are discarded when it grows).
  void reserve(size_t bytes);
  // Binds the buffer as GL_PIXEL_PACK_BUFFER: a glReadPixels /
  // glGetTextureImage now writes into it at the "pointer" offset given.
  void bindForPack() const;
  static void unbindPack();
  // After the frame's reads: a fence the map waits on.
  void fence();
  // Waits for the fence, maps the buffer for reading; nullptr with GL's
  // error if mapping failed. unmap() before the buffer is used again.
  const uint8_t* map();
  void unmap();
  void release();

 private:
  GLuint buffer_ = 0;
  size_t size_ = 0;
  GLsync fence_ = nullptr;
  bool mapped_ = false;
};

}  // namespace hs::render
