#pragma once
// The A-buffer capture (issue 13; shaders/abuffer.glsl is the GLSL side):
// draws a given draw list into per-pixel linked lists of fragments (Yang
// et al. 2010): head pointers (one uint per pixel), a node pool in a storage
// buffer (colour as two half pairs, depth, next node: 16 bytes) and an
// atomic counter. Shared by the transparency path (render/oit.h: the
// translucent submeshes, depth-tested against the opaque depth) and the
// layered depth of field (every surface, no depth test).
//
// Two passes, both through the frame graph, so the registry and --stats see
// every byte: "<name>_count" counts each pixel's fragments (the counts
// image, which is also the depth-complexity view) and the frame's total;
// the CPU reads the total back (one small wait) and sizes the pool for
// exactly this frame's fragments, capped by `memoryCapBytes`. Then
// "<name>_capture" draws the list again with the mesh shader's
// HS_OIT_ABUFFER variant (full lighting), appending each fragment to its
// pixel's list. Fragments beyond the pool's capacity (only when the cap is
// reached) are counted (ABufferInfo::overflow) and, with `tail`, summed into
// the tail buffer (shaders/oit_tail.glsl) instead of being dropped.
//
// Reading it: bind with bindABuffer in a later pass that reads the refs,
// and include shaders/abuffer_sort.glsl, which loads one pixel's list into
// a local array sorted front to back, in a compute shader (on llvmpipe a
// fragment shader's dynamically indexed array misread some pixels;
// shaders/oit_resolve.comp is the example). Include only inside render/.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/draw_list.h"
#include "render/frame_context.h"

namespace hs::render {

// Binding points (shaders/abuffer.glsl, oit_tail.glsl; reserved for oit:
// buffers 12-15, image units 0-3).
enum ABufferBinding : unsigned {
  kABufferCountsImage = 1,       // image unit: r32ui fragments per pixel
  kABufferNodesBinding = 12,     // buffer: uvec4 nodes
  kABufferCountersBinding = 13,  // buffer: ABufferCounters
  kOitTailBinding = 14,          // buffer: tail sums (two uvec4 per pixel)
  kABufferHeadsBinding = 15,     // buffer: uint head per pixel, row-major (a buffer, not an image: abuffer.glsl says why)
};
constexpr uint32_t kABufferEnd = 0xFFFFFFFFu;
constexpr size_t kABufferNodeBytes = 16;
constexpr size_t kOitTailBytesPerPixel = 32;

// The std430 ABufferCounters block (shaders/abuffer.glsl), member for member.
struct ABufferCounters {
  uint32_t allocated = 0, fragments = 0, maxPerPixel = 0, coveredPixels = 0;
  uint32_t capacity = 0, overflow = 0, tailShare = 0, tailPixels = 0;
  uint32_t width = 0, pad[3] = {0, 0, 0};
};
static_assert(sizeof(ABufferCounters) == 48);

// Zeroes a counters buffer and sets its width (the row length of the
// per-pixel buffers).
void resetABufferCounters(GLuint buffer, int width);

enum class ABufferDepthTest {
  Opaque,  // only fragments in front of the opaque depth (transparency)
  None,    // every fragment, the opaque surfaces behind the front included (depth of field)
};

struct ABufferRequest {
  std::string name = "abuffer";  // prefix of its passes and resources ("oit", "dof"); the view's suffix follows
  DrawList draws;
  // The view's single-sample opaque depth (reversed Z). It sizes the
  // buffers, and with ABufferDepthTest::Opaque fragments behind it are not
  // captured (it is attached read-only, never written).
  TextureRef depth;
  ABufferDepthTest depthTest = ABufferDepthTest::Opaque;
  size_t memoryCapBytes = size_t(256) << 20;  // heads + counts + pool (+ tail and result image) stay under this
  bool tail = false;   // sum what does not fit into the tail buffer (oit_tail.glsl)
  std::vector<std::string> defines;  // more defines for the capture's mesh program
};

// What the passes found, filled when they run (read it after the frame's execute).
struct ABufferInfo {
  int width = 0, height = 0;
  uint64_t fragments = 0;      // fragments that passed the depth test (counting pass)
  uint32_t maxPerPixel = 0;    // the deepest pixel's count
  uint64_t coveredPixels = 0;  // pixels with at least one fragment
  uint64_t capacity = 0;       // nodes in the pool
  uint64_t overflow = 0;       // fragments that found no node (fragments - capacity when positive)
  size_t bytes = 0;            // heads + counts + pool + counters (+ with a tail: the tail and the resolve's 16-byte result image)
  bool ran = false;
};

struct ABuffer {
  BufferRef heads;      // uint per pixel, row-major: newest node of the pixel, kABufferEnd for none
  TextureRef counts;    // r32ui: fragments per pixel
  BufferRef nodes;      // uvec4 per node
  BufferRef counters;   // ABufferCounters
  BufferRef tail;       // with ABufferRequest::tail; else invalid
  std::shared_ptr<ABufferInfo> info;
};

// The counting pass alone ("<name>_count"): each pixel's fragments of
// `draws` that pass `test` against `depth` into the counts image, the totals
// into the counters, read back into `info` (fragments, maxPerPixel,
// coveredPixels) when it runs. For the transparency modes that keep no
// list but report fragments per pixel, and the depth-complexity view.
struct FragmentCount {
  TextureRef counts;   // r32ui
  BufferRef counters;  // ABufferCounters
  std::shared_ptr<ABufferInfo> info;
};
FragmentCount addFragmentCountPass(FrameGraph& graph, FrameContext& frame, const ViewContext& view,
                                   const std::string& name, const DrawList& draws, TextureRef depth,
                                   ABufferDepthTest test);

// Adds the counting and capture passes for `view`. With an empty draw list
// it adds nothing and returns invalid refs (nothing is allocated).
ABuffer addABufferCapture(FrameGraph& graph, FrameContext& frame, const ViewContext& view, const ABufferRequest& request);

// Declares a later pass's reads of the A-buffer (heads, nodes, counters,
// counts, tail) and, in its execute, binds them where shaders/abuffer.glsl
// expects them.
void readABuffer(PassBuilder& b, const ABuffer& a);
void bindABuffer(const ABuffer& a, const PassResources& r);

}  // namespace hs::render
