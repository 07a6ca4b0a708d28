#include "render/pixel_readback.h"

namespace hs::render {

void PixelReadback::reserve(size_t bytes) {
  if (buffer_ && bytes <= size_) return;
  release();
  glCreateBuffers(1, &buffer_);
  // GL_STREAM_READ: written by the GPU once, read by the CPU once.
  glNamedBufferData(buffer_, GLsizeiptr(bytes), nullptr, GL_STREAM_READ);
  size_ = bytes;
}

void PixelReadback::bindForPack() const { glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer_); }
void PixelReadback::unbindPack() { glBindBuffer(GL_PIXEL_PACK_BUFFER, 0); }

void PixelReadback::fence() {
  if (fence_) glDeleteSync(fence_);
  fence_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  // Make sure the commands start now, so the GPU works while the caller
  // sets up the next frame.
  glFlush();
}

const uint8_t* PixelReadback::map() {
  if (!buffer_) return nullptr;
  if (fence_) {
    // Wait in slices of a second: a slow frame is not an error.
    while (glClientWaitSync(fence_, GL_SYNC_FLUSH_COMMANDS_BIT, 1000000000ull) == GL_TIMEOUT_EXPIRED) {
    }
    glDeleteSync(fence_);
    fence_ = nullptr;
  }
  void* p = glMapNamedBufferRange(buffer_, 0, GLsizeiptr(size_), GL_MAP_READ_BIT);
  mapped_ = p != nullptr;
  return static_cast<const uint8_t*>(p);
}

void PixelReadback::unmap() {
  if (mapped_) glUnmapNamedBuffer(buffer_);
  mapped_ = false;
}

void PixelReadback::release() {
  unmap();
  if (fence_) glDeleteSync(fence_);
  fence_ = nullptr;
  if (buffer_) glDeleteBuffers(1, &buffer_);
  buffer_ = 0;
  size_ = 0;
}

}  // namespace hs::render
