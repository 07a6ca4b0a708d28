#include "render/abuffer.h"

#include <algorithm>

#include "render/passes/light_culling.h"
#include "render/passes/shadow_passes.h"

namespace hs::render {
namespace {

// The depth state of a capture or counting draw: the opaque depth tested,
// never written.
void setDepthTest(ABufferDepthTest test) {
  glDepthMask(GL_FALSE);
  if (test == ABufferDepthTest::Opaque) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);  // reversed Z: in front of the opaque surface
  } else {
    glDisable(GL_DEPTH_TEST);
  }
}

void restoreDepthState() {
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_GREATER);
}

// Nodes the pool gets: every counted fragment, unless the cap says fewer;
// then the tail (with `tail`) is allocated too and its bytes come off the
// pool's share.
void sizePool(ABufferInfo& info, size_t capBytes, bool tail) {
  const size_t pixels = size_t(info.width) * size_t(info.height);
  const size_t fixed = 2 * pixels * 4 + sizeof(ABufferCounters) + (tail ? pixels * 16 : 0);  // + the resolve's result image
  size_t capacity = size_t(info.fragments);
  size_t tailBytes = 0;
  if (fixed + capacity * kABufferNodeBytes > capBytes) {
    tailBytes = tail ? pixels * kOitTailBytesPerPixel : 0;
    const size_t room = capBytes > fixed + tailBytes ? capBytes - fixed - tailBytes : 0;
    capacity = std::min(capacity, room / kABufferNodeBytes);
  }
  info.capacity = capacity;
  info.overflow = info.fragments > capacity ? info.fragments - capacity : 0;
  info.bytes = fixed + std::max<size_t>(capacity, 1) * kABufferNodeBytes + (tail ? std::max<size_t>(tailBytes, 32) : 0);
}

}  // namespace

void resetABufferCounters(GLuint buffer, int width) {
  const GLuint zero = 0, w = GLuint(width);
  glClearNamedBufferData(buffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glNamedBufferSubData(buffer, offsetof(ABufferCounters, width), 4, &w);
}

FragmentCount addFragmentCountPass(FrameGraph& graph, FrameContext& frame, const ViewContext& v,
                                   const std::string& name, const DrawList& draws, TextureRef depth,
                                   ABufferDepthTest test) {
  FragmentCount out;
  out.info = std::make_shared<ABufferInfo>();
  out.info->width = v.view.width;
  out.info->height = v.view.height;
  struct Count {
    TextureRef depth, counts;
    BufferRef counters;
  };
  const Count& count = graph.addPass<Count>(
      v.named(name + "_count"),
      [&](PassBuilder& b, Count& d) {
        d.depth = b.read(depth);
        d.counts = b.create(v.named(name + "_counts"), TextureDesc{v.view.width, v.view.height, GL_R32UI});
        d.counters = b.create(v.named(name + "_counters"), BufferDesc{sizeof(ABufferCounters)});
      },
      [&frame, info = out.info, index = v.index, draws, test](const Count& d, const PassResources& r) {
        const GLuint zero = 0;
        glClearTexImage(r.texture(d.counts), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        resetABufferCounters(r.buffer(d.counters), info->width);
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({}, d.depth));
        glViewport(0, 0, info->width, info->height);
        setDepthTest(test);
        frame.res.bindView(index);
        glBindImageTexture(kABufferCountsImage, r.texture(d.counts), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferCountersBinding, r.buffer(d.counters));
        drawSubmeshes(frame, draws, {}, "abuffer_count.frag");
        restoreDepthState();
        // Read back now: the A-buffer sizes its pool from it before the
        // capture (the frame's one wait for the GPU in between).
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        ABufferCounters c;
        glGetNamedBufferSubData(r.buffer(d.counters), 0, sizeof c, &c);
        info->fragments = c.fragments;
        info->maxPerPixel = c.maxPerPixel;
        info->coveredPixels = c.coveredPixels;
        info->bytes = 2 * size_t(info->width) * size_t(info->height) * 4 + sizeof(ABufferCounters);
      });
  out.counts = count.counts;
  out.counters = count.counters;
  return out;
}

ABuffer addABufferCapture(FrameGraph& graph, FrameContext& frame, const ViewContext& v, const ABufferRequest& request) {
  ABuffer out;
  if (request.draws.empty()) return out;
  const FragmentCount count =
      addFragmentCountPass(graph, frame, v, request.name, request.draws, request.depth, request.depthTest);
  const std::shared_ptr<ABufferInfo> info = count.info;
  out.info = info;
  const int w = v.view.width, h = v.view.height;

  struct Capture {
    TextureRef depth, counts;
    BufferRef heads, nodes, counters, tail;
  };
  const Capture& cap = graph.addPass<Capture>(
      v.named(request.name + "_capture"),
      [&](PassBuilder& b, Capture& d) {
        d.depth = b.read(request.depth);
        d.counts = b.read(count.counts);
        d.counters = b.write(b.read(count.counters));
        d.heads = b.create(v.named(request.name + "_heads"), BufferDesc{size_t(w) * size_t(h) * 4});
        d.nodes = b.createSized(v.named(request.name + "_nodes"), [info, cap = request.memoryCapBytes,
                                                                   tail = request.tail] {
          sizePool(*info, cap, tail);  // the counting pass has run
          return BufferDesc{std::max<size_t>(info->capacity, 1) * kABufferNodeBytes};
        });
        if (request.tail)
          d.tail = b.createSized(v.named(request.name + "_tail"), [info] {
            const size_t pixels = size_t(info->width) * size_t(info->height);
            return BufferDesc{info->overflow ? pixels * kOitTailBytesPerPixel : 32};
          });
        readShadowMaps(b, frame);
        readLightGrid(b, frame);
      },
      [&frame, info, index = v.index, draws = request.draws, test = request.depthTest, tail = request.tail,
       extra = request.defines](const Capture& d, const PassResources& r) {
        const GLuint end = kABufferEnd, zero = 0;
        glClearNamedBufferData(r.buffer(d.heads), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &end);
        const uint32_t capacity = uint32_t(info->capacity);
        glNamedBufferSubData(r.buffer(d.counters), offsetof(ABufferCounters, allocated), 4, &zero);
        glNamedBufferSubData(r.buffer(d.counters), offsetof(ABufferCounters, capacity), 4, &capacity);
        if (tail) glClearNamedBufferData(r.buffer(d.tail), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({}, d.depth));
        glViewport(0, 0, info->width, info->height);
        setDepthTest(test);
        frame.res.bindView(index);
        bindShadowMaps(frame, r);
        bindLightGrid(frame, r, index);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferHeadsBinding, r.buffer(d.heads));
        glBindImageTexture(kABufferCountsImage, r.texture(d.counts), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferNodesBinding, r.buffer(d.nodes));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferCountersBinding, r.buffer(d.counters));
        if (tail) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOitTailBinding, r.buffer(d.tail));
        std::vector<std::string> defines = surfaceDefines(frame);
        defines.push_back("HS_OIT");
        defines.push_back("HS_OIT_ABUFFER");
        if (tail) defines.push_back("HS_OIT_TAIL");
        defines.insert(defines.end(), extra.begin(), extra.end());
        drawSubmeshes(frame, draws, defines);
        restoreDepthState();
        // Link the appended nodes into their pixels' lists
        // (shaders/abuffer_link.comp says why not in the capture).
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        if (const GLuint nodes = GLuint(std::min(info->fragments, info->capacity))) {
          frame.res.program({"", "", "abuffer_link.comp", {}}).use();
          glDispatchCompute((nodes + 63) / 64, 1, 1);
        }
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                        GL_BUFFER_UPDATE_BARRIER_BIT);
        info->ran = true;
      });
  out.heads = cap.heads;
  out.counts = cap.counts;
  out.nodes = cap.nodes;
  out.counters = cap.counters;
  out.tail = cap.tail;
  return out;
}

void readABuffer(PassBuilder& b, const ABuffer& a) {
  b.read(a.heads);
  b.read(a.counts);
  b.read(a.nodes);
  b.read(a.counters);
  if (a.tail.valid()) b.read(a.tail);
}

void bindABuffer(const ABuffer& a, const PassResources& r) {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferHeadsBinding, r.buffer(a.heads));
  glBindImageTexture(kABufferCountsImage, r.texture(a.counts), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferNodesBinding, r.buffer(a.nodes));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferCountersBinding, r.buffer(a.counters));
  if (a.tail.valid()) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOitTailBinding, r.buffer(a.tail));
}

}  // namespace hs::render
