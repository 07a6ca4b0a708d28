#include "render/abuffer.h"

#include <algorithm>
#include <utility>

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

// Bytes of everything but the pool: starts (one more than the pixels),
// cursor, counts, counters, and with a tail the resolve's RGBA32F result.
size_t fixedBytes(size_t pixels, bool tail) {
  return (pixels + 1) * 4 + 2 * pixels * 4 + sizeof(ABufferCounters) + (tail ? pixels * 16 : 0);
}

// The largest per-pixel cap whose nodes fit `room` nodes, and the nodes it
// keeps: sum over pixels of min(count, cap) is non-decreasing in the cap,
// so a binary search on it finds the cap.
std::pair<uint32_t, uint64_t> perPixelCap(const std::vector<uint32_t>& counts, uint32_t maxPerPixel, uint64_t room) {
  auto kept = [&](uint32_t cap) {
    uint64_t sum = 0;
    for (uint32_t c : counts) sum += std::min(c, cap);
    return sum;
  };
  uint32_t lo = 0, hi = maxPerPixel;  // kept(lo) fits; find the largest that does
  while (lo < hi) {
    const uint32_t mid = lo + (hi - lo + 1) / 2;
    if (kept(mid) <= room) lo = mid;
    else hi = mid - 1;
  }
  return {lo, kept(lo)};
}

// Nodes the pool gets: every counted fragment, unless the cap says fewer;
// then the tail (with `tail`) is allocated too and its bytes come off the
// pool's share, and each pixel keeps its nearest `perPixelCap` fragments.
void sizePool(ABufferInfo& info, size_t capBytes, bool tail) {
  const size_t pixels = size_t(info.width) * size_t(info.height);
  const size_t fixed = fixedBytes(pixels, tail);
  size_t capacity = size_t(info.fragments);
  size_t tailBytes = 0;
  info.perPixelCap = kABufferNoCap;
  if (info.fixedLayers) {
    capacity = pixels * info.fixedLayers;
    info.perPixelCap = info.fixedLayers;
    uint64_t over = 0;
    for (uint32_t c : info.pixelCounts) over += c > info.fixedLayers ? c - info.fixedLayers : 0;
    tailBytes = tail && over ? pixels * kOitTailBytesPerPixel : 0;
    info.pixelCounts = {};
    info.capacity = capacity;
    info.overflow = over;
    info.bytes = fixed + capacity * kABufferNodeBytes + (tail ? std::max<size_t>(tailBytes, kOitTailBytesPerPixel) : 0);
    return;
  }
  // Buffers are made in size classes (resource_pool.h), at most 1/8 over
  // what they ask: asking for 8/9 of the cap keeps what is allocated
  // within it.
  const size_t budget = capBytes / 9 * 8;
  if (fixed + capacity * kABufferNodeBytes > budget) {
    tailBytes = tail ? pixels * kOitTailBytesPerPixel : 0;
    const size_t room = budget > fixed + tailBytes ? (budget - fixed - tailBytes) / kABufferNodeBytes : 0;
    const auto [cap, kept] = perPixelCap(info.pixelCounts, info.maxPerPixel, room);
    info.perPixelCap = cap;
    capacity = kept;
  }
  info.pixelCounts = {};
  info.capacity = capacity;
  info.overflow = info.fragments > capacity ? info.fragments - capacity : 0;
  info.bytes = fixed + std::max<size_t>(capacity, 1) * kABufferNodeBytes +
               (tail ? std::max<size_t>(tailBytes, kOitTailBytesPerPixel) : 0);
}

}  // namespace

void resetABufferCounters(GLuint buffer, int width) {
  const GLuint zero = 0, w = GLuint(width);
  glClearNamedBufferData(buffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glNamedBufferSubData(buffer, offsetof(ABufferCounters, width), 4, &w);
}

FragmentCount addFragmentCountPass(FrameGraph& graph, FrameContext& frame, const ViewContext& v,
                                   const std::string& name, SurfaceSet draws, TextureRef depth,
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
        declareSources(b, frame, DrawVariant::Surface, draws);
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
        drawSurfaces(frame, r, index, draws, {}, "abuffer_count.frag");
        restoreDepthState();
        // Read back now: the A-buffer sizes its pool from it before the
        // capture (the frame's one wait for the GPU in between).
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        ABufferCounters c;
        glGetNamedBufferSubData(r.buffer(d.counters), 0, sizeof c, &c);
        info->fragments = c.fragments;
        info->maxPerPixel = c.maxPerPixel;
        info->coveredPixels = c.coveredPixels;
        const size_t pixels = size_t(info->width) * size_t(info->height);
        info->bytes = 2 * pixels * 4 + sizeof(ABufferCounters);
        if ((info->poolBudgetBytes && size_t(info->fragments) * kABufferNodeBytes > info->poolBudgetBytes) ||
            (info->fixedLayers && info->maxPerPixel > info->fixedLayers)) {
          // The pool will not hold every fragment: each pixel's count, for
          // the per-pixel cap or the overflow (sizePool).
          info->pixelCounts.resize(pixels);
          glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
          glGetTextureImage(r.texture(d.counts), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(pixels * 4),
                            info->pixelCounts.data());
        }
      });
  out.counts = count.counts;
  out.counters = count.counters;
  return out;
}

ABuffer addABufferCapture(FrameGraph& graph, FrameContext& frame, const ViewContext& v, const ABufferRequest& request) {
  ABuffer out;
  if (!anySource(frame, DrawVariant::Surface, request.draws)) return out;
  const FragmentCount count =
      addFragmentCountPass(graph, frame, v, request.name, request.draws, request.depth, request.depthTest);
  const std::shared_ptr<ABufferInfo> info = count.info;
  out.info = info;
  const int w = v.view.width, h = v.view.height;
  const size_t pixels = size_t(w) * size_t(h);
  const size_t fixed = fixedBytes(pixels, request.tail);
  if (request.fixedLayers > 0) {
    // The layers the cap holds beside everything else (the tail included).
    const size_t tailBytes = request.tail ? pixels * kOitTailBytesPerPixel : 0;
    const size_t room = request.memoryCapBytes > fixed + tailBytes ? request.memoryCapBytes - fixed - tailBytes : 0;
    info->fixedLayers = uint32_t(std::clamp<size_t>(room / (kABufferNodeBytes * std::max<size_t>(pixels, 1)), 1,
                                                    size_t(request.fixedLayers)));
  } else {
    info->poolBudgetBytes = request.memoryCapBytes > fixed ? request.memoryCapBytes - fixed : 1;
  }

  struct Capture {
    TextureRef depth, counts;
    BufferRef starts, cursor, nodes, counters, tail;
  };
  const Capture& cap = graph.addPass<Capture>(
      v.named(request.name + "_capture"),
      [&](PassBuilder& b, Capture& d) {
        declareSources(b, frame, DrawVariant::Surface, request.draws);
        d.depth = b.read(request.depth);
        d.counts = b.read(count.counts);
        d.counters = b.write(b.read(count.counters));
        d.starts = b.create(v.named(request.name + "_starts"), BufferDesc{(pixels + 1) * 4});
        d.cursor = b.create(v.named(request.name + "_cursor"), BufferDesc{pixels * 4});
        d.nodes = b.createSized(v.named(request.name + "_nodes"), [info, cap = request.memoryCapBytes,
                                                                   tail = request.tail] {
          sizePool(*info, cap, tail);  // the counting pass has run
          return BufferDesc{std::max<size_t>(info->capacity, 1) * kABufferNodeBytes};
        });
        if (request.tail)
          d.tail = b.createSized(v.named(request.name + "_tail"), [info, pixels] {
            return BufferDesc{info->overflow ? pixels * kOitTailBytesPerPixel : kOitTailBytesPerPixel};
          });
        readShadowMaps(b, frame);
        readLightGrid(b, frame);
      },
      [&frame, info, index = v.index, draws = request.draws, test = request.depthTest, tail = request.tail,
       extra = request.defines, w, h](const Capture& d, const PassResources& r) {
        const GLuint zero = 0, empty = 0xFFFFFFFFu;
        const uint32_t capacity = uint32_t(info->capacity), perPixel = info->perPixelCap, layers = info->fixedLayers;
        glNamedBufferSubData(r.buffer(d.counters), offsetof(ABufferCounters, perPixelCap), 4, &perPixel);
        glNamedBufferSubData(r.buffer(d.counters), offsetof(ABufferCounters, fixedLayers), 4, &layers);
        glNamedBufferSubData(r.buffer(d.counters), offsetof(ABufferCounters, capacity), 4, &capacity);
        // Every node's key empty (the cap's atomicMin chain) and depth unwritten.
        glClearNamedBufferData(r.buffer(d.nodes), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
        if (tail) glClearNamedBufferData(r.buffer(d.tail), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        glBindImageTexture(kABufferCountsImage, r.texture(d.counts), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferStartsBinding, r.buffer(d.starts));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferCursorBinding, r.buffer(d.cursor));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferNodesBinding, r.buffer(d.nodes));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferCountersBinding, r.buffer(d.counters));
        if (tail) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOitTailBinding, r.buffer(d.tail));

        // 1. The ranges: row sums, then starts (abuffer_scan.comp).
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        for (const char* step : {"ABUFFER_SCAN_ROW_SUMS", "ABUFFER_SCAN_STARTS"}) {
          GlProgram& scan = frame.res.program({"", "", "abuffer_scan.comp", {step}});
          scan.use();
          scan.set("uSize", glm::ivec2(w, h));
          glDispatchCompute(GLuint(h + 63) / 64, 1, 1);
          glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        }
        glClearNamedBufferData(r.buffer(d.cursor), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);

        // 2. Keys into nodes (abuffer_keys.frag).
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({}, d.depth));
        glViewport(0, 0, w, h);
        setDepthTest(test);
        frame.res.bindView(index);
        drawSurfaces(frame, r, index, draws, {}, "abuffer_keys.frag");
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

        // 3. Each pixel's keys in order (abuffer_sort_keys.comp).
        GlProgram& sort = frame.res.program({"", "", "abuffer_sort_keys.comp", {}});
        sort.use();
        sort.set("uSize", glm::ivec2(w, h));
        glDispatchCompute(GLuint(w + 7) / 8, GLuint(h + 7) / 8, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

        // 4. The lit pass: each fragment's colour and depth into its node.
        frame.res.bindView(index);
        bindShadowMaps(frame, r);
        bindLightGrid(frame, r, index);
        std::vector<std::string> defines = surfaceDefines(frame);
        defines.push_back("HS_OIT");
        defines.push_back("HS_OIT_ABUFFER");
        if (tail) defines.push_back("HS_OIT_TAIL");
        defines.insert(defines.end(), extra.begin(), extra.end());
        drawSurfaces(frame, r, index, draws, defines);
        restoreDepthState();
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                        GL_BUFFER_UPDATE_BARRIER_BIT);
        info->ran = true;
      });
  out.starts = cap.starts;
  out.counts = cap.counts;
  out.nodes = cap.nodes;
  out.counters = cap.counters;
  out.tail = cap.tail;
  return out;
}

void readABuffer(PassBuilder& b, const ABuffer& a) {
  b.read(a.starts);
  b.read(a.counts);
  b.read(a.nodes);
  b.read(a.counters);
  if (a.tail.valid()) b.read(a.tail);
}

void bindABuffer(const ABuffer& a, const PassResources& r) {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferStartsBinding, r.buffer(a.starts));
  glBindImageTexture(kABufferCountsImage, r.texture(a.counts), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferNodesBinding, r.buffer(a.nodes));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kABufferCountersBinding, r.buffer(a.counters));
  if (a.tail.valid()) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOitTailBinding, r.buffer(a.tail));
}

}  // namespace hs::render
