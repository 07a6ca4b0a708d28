#pragma once
// The A-buffer capture (issue 13; shaders/abuffer.glsl is the GLSL side):
// draws a set of the frame's surfaces (draw_source.h: every source's
// Surface variant) into per-pixel ranges of fragments: a node pool
// in a storage buffer (colour as two half pairs, depth, key: 16 bytes per
// fragment) where each pixel's fragments are contiguous and sorted front to
// back, and the starts of the ranges (one uint per pixel). Shared by the
// transparency path (render/oit.h: the translucent submeshes, depth-tested
// against the opaque depth) and the layered depth of field (every surface,
// no depth test).
//
// Two frame-graph passes, so the registry and --stats see every byte:
// "<name>_count" counts each pixel's fragments (the counts image, which is
// also the depth-complexity view) and the frame's total; the CPU reads the
// total back (one small wait) and sizes the pool for exactly this frame's
// fragments, capped by `memoryCapBytes`. "<name>_capture" then
//   1. turns the counts into ranges (a prefix sum, shaders/abuffer_scan.comp),
//   2. draws the surfaces with a derivative-free shader that hands each
//      fragment a node of its pixel and writes its depth and key there
//      (shaders/abuffer_keys.frag, which says why not in the lit shader),
//   3. sorts each pixel's range by depth (shaders/abuffer_sort_keys.comp),
//   4. draws them again with the mesh shader's HS_OIT_ABUFFER variant
//      (full lighting): each fragment finds its node and writes its colour.
// No step depends on the order fragments arrive in, so a frame captures
// the same bits every time (the linked lists of Yang et al. 2010, built
// with atomics in the lit shader, did not on llvmpipe). When the cap is
// reached each pixel keeps its nearest `perPixelCap` fragments (the largest
// cap that fits); the rest are counted (ABufferInfo::overflow) and, with
// `tail`, summed into the tail buffer (shaders/oit_tail.glsl) instead of
// being dropped.
//
// Reading it: bind with bindABuffer in a later pass that reads the refs and
// walk a pixel's range (shaders/abuffer_read.glsl), in a compute shader
// (on llvmpipe a fragment shader's dynamically indexed array misread some
// pixels; shaders/oit_resolve.comp is the example). Include only inside
// render/.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/draw_source.h"
#include "render/frame_context.h"

namespace hs::render {

// Binding points (shaders/abuffer.glsl, oit_tail.glsl; reserved for oit:
// buffers 12-16, image units 0-3).
enum ABufferBinding : unsigned {
  kABufferCountsImage = 1,       // image unit: r32ui fragments per pixel
  kABufferNodesBinding = 12,     // buffer: uvec4 nodes
  kABufferCountersBinding = 13,  // buffer: ABufferCounters
  kOitTailBinding = 14,          // buffer: tail sums (three uvec4 per pixel: shaders/oit_tail.glsl)
  kABufferStartsBinding = 15,    // buffer: uint per pixel and one more, row-major: where each pixel's range starts
  kABufferCursorBinding = 16,    // buffer: uint per pixel, the key pass's next node (the capture's alone)
};
constexpr uint32_t kABufferNoCap = 0xFFFFFFFFu;
constexpr size_t kABufferNodeBytes = 16;
constexpr size_t kOitTailBytesPerPixel = 48;

// The std430 ABufferCounters block (shaders/abuffer.glsl), member for member.
struct ABufferCounters {
  uint32_t perPixelCap = kABufferNoCap, fragments = 0, maxPerPixel = 0, coveredPixels = 0;
  uint32_t capacity = 0, overflow = 0, tailShare = 0, tailPixels = 0;
  uint32_t width = 0, fixedLayers = 0, pad[2] = {0, 0};
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
  SurfaceSet draws = SurfaceSet::Translucent;  // which surfaces of the frame's sources
  // The view's single-sample opaque depth (reversed Z). It sizes the
  // buffers, and with ABufferDepthTest::Opaque fragments behind it are not
  // captured (it is attached read-only, never written).
  TextureRef depth;
  ABufferDepthTest depthTest = ABufferDepthTest::Opaque;
  size_t memoryCapBytes = size_t(256) << 20;  // starts + cursor + counts + pool (+ tail and result image) stay under this
  bool tail = false;   // sum what does not fit into the tail buffer (oit_tail.glsl)
  // The thesis's fixed-depth array (abuffer_fixed): every pixel gets this
  // many nodes whatever it needs (fewer when the cap says so), a pixel
  // with more keeps its nearest. 0: the pool is sized to the frame.
  int fixedLayers = 0;
  std::vector<std::string> defines;  // more defines for the capture's mesh program
};

// What the passes found, filled when they run (read it after the frame's execute).
struct ABufferInfo {
  int width = 0, height = 0;
  uint64_t fragments = 0;      // fragments that passed the depth test (counting pass)
  uint32_t maxPerPixel = 0;    // the deepest pixel's count
  uint64_t coveredPixels = 0;  // pixels with at least one fragment
  uint64_t capacity = 0;       // nodes in the pool
  uint32_t perPixelCap = kABufferNoCap;  // nodes a pixel may keep (the largest that fits the memory cap)
  uint32_t fixedLayers = 0;    // the fixed array's nodes per pixel (ABufferRequest::fixedLayers under the cap); 0: none
  uint64_t overflow = 0;       // fragments that found no node (fragments - capacity when positive)
  size_t bytes = 0;            // starts + cursor + counts + pool + counters (+ with a tail: the tail and the resolve's 16-byte result image)
  bool ran = false;
  // Set before the counting pass runs: over this many bytes of pool, or
  // with a pixel deeper than `fixedLayers`, the pass also reads every
  // pixel's count back into `pixelCounts`, from which the pool's sizing
  // finds the per-pixel cap or the fixed array's overflow (0: never).
  size_t poolBudgetBytes = 0;
  std::vector<uint32_t> pixelCounts;
};

struct ABuffer {
  BufferRef starts;     // uint per pixel and one more, row-major: pixel i's nodes are [starts[i], starts[i + 1])
  TextureRef counts;    // r32ui: fragments per pixel
  BufferRef nodes;      // uvec4 per node, each pixel's sorted front to back
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
                                   const std::string& name, SurfaceSet draws, TextureRef depth,
                                   ABufferDepthTest test);

// Adds the counting and capture passes for `view`. With no source having
// such surfaces it adds nothing and returns invalid refs (nothing is allocated).
ABuffer addABufferCapture(FrameGraph& graph, FrameContext& frame, const ViewContext& view, const ABufferRequest& request);

// Declares a later pass's reads of the A-buffer (starts, nodes, counters,
// counts, tail) and, in its execute, binds them where shaders/abuffer.glsl
// expects them.
void readABuffer(PassBuilder& b, const ABuffer& a);
void bindABuffer(const ABuffer& a, const PassResources& r);

}  // namespace hs::render
