#include "render/render_resources.h"

#include <algorithm>
#include <cstdio>
#include <numeric>

namespace hs::render {

bool GrowingBuffer::reserve(size_t bytes, size_t minimum) {
  bytes = std::max(bytes, minimum);
  if (buffer && bytes <= capacity) return false;
  capacity = std::max(bytes, capacity * 2);
  buffer = gl::createBuffer();
  glNamedBufferStorage(buffer.id(), GLsizeiptr(capacity), nullptr, GL_DYNAMIC_STORAGE_BIT);
  return true;
}

void GrowingBuffer::upload(const void* data, size_t bytes, size_t offset) {
  reserve(offset + bytes);
  if (bytes) glNamedBufferSubData(buffer.id(), GLintptr(offset), GLsizeiptr(bytes), data);
}

GlProgram& RenderResources::program(const gl::ProgramDesc& desc) {
  std::string error;
  GlProgram* p = shaders.get(desc, error);
  if (!p) {
    // Every program is built by Renderer::initialize, which refuses to start
    // if one fails; reaching here is a renderer bug, not bad input.
    std::fprintf(stderr, "hybridscape: internal error: %s\n", error.c_str());
    std::abort();
  }
  return *p;
}

void RenderResources::ensureObjectIndices(size_t count) {
  if (count <= objectIndexCount && objectIndices.buffer) return;
  const size_t n = std::max<size_t>(count, std::max<size_t>(objectIndexCount * 2, 1024));
  std::vector<uint32_t> idx(n);
  std::iota(idx.begin(), idx.end(), 0u);
  objectIndices.buffer.reset();
  objectIndices.capacity = 0;
  objectIndices.upload(idx.data(), idx.size() * sizeof(uint32_t));
  objectIndexCount = n;
  meshes.setObjectIndexBuffer(objectIndices.buffer.id());
}

void RenderResources::bindView(size_t index) const {
  glBindBufferRange(GL_UNIFORM_BUFFER, kViewBlockBinding, viewBlocks.buffer.id(), GLintptr(index * viewStride),
                    sizeof(ViewBlock));
}

void RenderResources::bindFrame() const {
  glBindBufferRange(GL_UNIFORM_BUFFER, kFrameBlockBinding, frameBlock.buffer.id(), 0, sizeof(FrameBlock));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLightBufferBinding, lights.buffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kObjectBufferBinding, objects.buffer.id());
}

}  // namespace hs::render
