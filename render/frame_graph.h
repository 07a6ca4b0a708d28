#pragma once
// A frame as a graph of passes (DESIGN.md; after Filament's FrameGraph).
//
// Each frame, the renderer adds its passes in order. A pass declares, in its
// setup, the textures and buffers it creates, reads and writes; its execute
// function then runs with those resources made real. Before anything runs,
// compile() culls: a pass is kept only if it has a side effect (it draws
// into the caller's framebuffer, reads pixels back) or something a kept pass
// reads, or a resource the frame keeps, comes from it. A culled pass does not
// run, and a resource no kept pass touches is never allocated. Transient
// resources come from the ResourcePool when their first pass runs and go
// back after their last, so a later pass (the other eye, the next frame)
// can reuse the memory.
//
// Writes make versions: a pass that blends onto the scene colour reads one
// version and writes the next, so only the passes whose output is really
// read stay alive, whatever order they were added in. A reference carries
// the version it names: write() returns the new one, and reading through a
// reference that a later write has replaced (a pass that would see content
// its author did not mean) is an error in strict mode (debug builds, tests:
// FrameGraph::setStrictVersions) and read as the latest version otherwise.
//
// Each access says how the pass uses the resource (Usage). From that the
// graph places the memory barriers between passes: a write through images
// or storage buffers (incoherent in GL) is made visible to the next pass
// that reads it, with the barrier bits of that pass's use (indirect
// commands, vertex data, texture fetches, ...), once. Barriers within one
// pass (a compute dispatch read by the next dispatch) stay the pass's own.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "render/resource_pool.h"

namespace hs::render {

// A resource of the frame and the version of it a pass means. Version 0
// is "whatever is current" (references made before versions were tracked,
// or by code that does not care); create(), write() and the imports return
// the exact version.
struct TextureRef {
  uint32_t index = UINT32_MAX;
  uint32_t version = 0;
  bool valid() const { return index != UINT32_MAX; }
};
struct BufferRef {
  uint32_t index = UINT32_MAX;
  uint32_t version = 0;
  bool valid() const { return index != UINT32_MAX; }
};

// How a pass uses a resource; decides the barriers the graph places.
enum class Usage : uint32_t {
  RenderTarget = 1u << 0,  // framebuffer attachment (colour, depth)
  Sampled = 1u << 1,       // texture fetch
  Storage = 1u << 2,       // image load/store, shader storage buffer, atomics
  Indirect = 1u << 3,      // glDraw*Indirect / glDispatchComputeIndirect commands
  Vertex = 1u << 4,        // vertex attributes or element indices
  Uniform = 1u << 5,       // uniform buffer
  Readback = 1u << 6,      // glGetTexImage, glGetBufferSubData, pixel pack
  Transfer = 1u << 7,      // glCopy*, glClearBuffer*, glBlit*, buffer uploads
};
constexpr Usage operator|(Usage a, Usage b) { return Usage(uint32_t(a) | uint32_t(b)); }
constexpr bool any(Usage a, Usage b) { return (uint32_t(a) & uint32_t(b)) != 0; }
// The glMemoryBarrier bits that make earlier incoherent writes visible to
// a use of `u` (of a texture when `texture`, else of a buffer).
GLbitfield barrierBitsFor(Usage u, bool texture);

class FrameGraph;

// Given to a pass's setup: what it uses.
class PassBuilder {
 public:
  TextureRef create(const std::string& name, const TextureDesc& desc, Usage usage = Usage::RenderTarget);
  BufferRef create(const std::string& name, const BufferDesc& desc, Usage usage = Usage::Storage);
  // A buffer whose size an earlier pass of the same frame decides (the
  // A-buffer's node pool, sized by its counting pass): `desc` is asked when
  // the buffer's first pass is about to run, after every pass before it ran.
  BufferRef createSized(const std::string& name, std::function<BufferDesc()> desc, Usage usage = Usage::Storage);
  TextureRef read(TextureRef t, Usage usage = Usage::Sampled);
  TextureRef write(TextureRef t, Usage usage = Usage::RenderTarget);
  BufferRef read(BufferRef b, Usage usage = Usage::Storage);
  BufferRef write(BufferRef b, Usage usage = Usage::Storage);
  // The pass changes something outside the graph (the caller's framebuffer,
  // a readback, a query): it always runs.
  void sideEffect();

 private:
  friend class FrameGraph;
  PassBuilder(FrameGraph& g, uint32_t pass) : graph_(g), pass_(pass) {}
  // Records a read or write of `index`; returns the version it names. A
  // read through a replaced `version` throws or is recorded (strict mode).
  uint32_t access(uint32_t index, uint32_t version, bool write, Usage usage);
  FrameGraph& graph_;
  uint32_t pass_;
};

// Given to a pass's execute: the GL objects behind its references.
class PassResources {
 public:
  GLuint texture(TextureRef t) const;
  GLuint buffer(BufferRef b) const;
  const TextureDesc& desc(TextureRef t) const;
  const BufferDesc& desc(BufferRef b) const;
  // A framebuffer with these attachments (cached by the pool): `layer` >= 0
  // attaches one layer of an array texture, `level` a mip level (a bloom
  // chain renders into each level of one texture).
  GLuint framebuffer(const std::vector<TextureRef>& colors, TextureRef depth = {}, int layer = -1,
                     int level = 0) const;
  // A sampler object with this state (made once, cached by the pool).
  GLuint sampler(const SamplerDesc& s) const;
  // True the first frame a persistent resource exists (or after its
  // description changed): its content is undefined and the pass must fill it.
  bool fresh(TextureRef t) const;
  bool fresh(BufferRef b) const;

 private:
  friend class FrameGraph;
  explicit PassResources(const FrameGraph& g) : graph_(g) {}
  const FrameGraph& graph_;
};

// What happened to a pass in the last frame.
struct PassRecord {
  std::string name;
  bool ran = false;
  double cpuMs = 0.0;
  double gpuMs = -1.0;    // from timestamps, when measured
  size_t gpuBytes = 0;    // transient resources first used by this pass
  GLbitfield barriers = 0;  // the memory barrier the graph placed before it (0: none)
};

class FrameGraph {
 public:
  using Execute = std::function<void(const PassResources&)>;

  explicit FrameGraph(ResourcePool& pool) : pool_(pool) {}
  FrameGraph(const FrameGraph&) = delete;
  FrameGraph& operator=(const FrameGraph&) = delete;

  // A texture made elsewhere and kept across frames (shadow maps, the
  // environment), used by passes like a transient one but never pooled.
  TextureRef importTexture(const std::string& name, GLuint texture, const TextureDesc& desc);
  BufferRef importBuffer(const std::string& name, GLuint buffer, const BufferDesc& desc);
  // A resource that lives across frames inside the graph (instance buffers,
  // page pools, history): found by `name` in the pool, made on first use or
  // when `desc` changes (PassResources::fresh says so), freed when a frame
  // goes by `lifetimeFrames` frames without asking for it. Its content from
  // the last frame is version 1 of this one.
  TextureRef persistentTexture(const std::string& name, const TextureDesc& desc, int lifetimeFrames = 1);
  BufferRef persistentBuffer(const std::string& name, const BufferDesc& desc, int lifetimeFrames = 1);

  // Copies `bytes` of `b` (from `offset`) into a staging buffer after the
  // passes before this call, behind a fence; `deliver` is called once the
  // GPU is done, from ResourcePool::pollReadbacks (each frame's start, so a
  // frame later, or later), never stalling this frame. For statistics and
  // streaming requests. The copying pass always runs.
  void readback(const std::string& name, BufferRef b, size_t offset, size_t bytes,
                std::function<void(const void* data, size_t bytes)> deliver);

  // Adds a pass: setup(builder, data) runs now and fills the pass's Data
  // (the references it created or uses); execute(data, resources) runs in
  // execute() if the pass survives culling. Returns the pass's data, which
  // lives as long as the graph (later passes read its references).
  template <class Data, class SetupFn, class ExecuteFn>
  const Data& addPass(const std::string& name, SetupFn&& setup, ExecuteFn&& execute) {
    auto data = std::make_shared<Data>();
    const uint32_t index = beginPass(name);
    PassBuilder builder(*this, index);
    setup(builder, *data);
    passes_[index].execute = [data, run = std::forward<ExecuteFn>(execute)](const PassResources& r) { run(*data, r); };
    return *data;
  }

  // The frame keeps this resource's last version after it has run
  // (readHdr after a frame): it counts as read, and it goes back to the
  // pool only when the graph is destroyed or reset.
  void keep(TextureRef t);
  void keep(BufferRef b);

  // Culls and runs every needed pass in the order they were added.
  // `timestamps` wraps each pass in GPU timestamp queries, fenced with
  // glFinish on both sides so the interval is the pass's own work on any
  // driver, and waits for them at the end (for --stats, the editor's
  // per-pass list one frame in 30, and benchmarks; it serialises the frame).
  void execute(bool timestamps = false);

  const std::vector<PassRecord>& records() const { return records_; }
  // Texture of a kept resource after execute (0 if it was never made).
  GLuint keptTexture(TextureRef t) const;
  GLuint keptBuffer(BufferRef b) const;
  // Returns kept resources to the pool and forgets the frame.
  void reset();
  ~FrameGraph() { reset(); }

  // Strict versions: reading through a replaced version throws
  // std::logic_error naming the pass and the resource. On by default in
  // debug builds (and with HS_FRAME_GRAPH_STRICT=1 in the environment).
  static void setStrictVersions(bool on);
  static bool strictVersions();
  // Stale reads seen (strict mode off), for tests and --stats.
  const std::vector<std::string>& staleReads() const { return staleReads_; }

 private:
  friend class PassBuilder;
  friend class PassResources;
  struct Resource {
    std::string name;
    bool texture = true;
    TextureDesc tdesc;
    BufferDesc bdesc;
    std::function<BufferDesc()> lateDesc;  // createSized: asked at allocation
    GLuint imported = 0;   // nonzero: made elsewhere (or persistent: the pool's)
    bool persistent = false;
    bool fresh = false;    // persistent, made this frame
    GLuint id = 0;         // while allocated
    uint32_t version = 0;  // current version during setup
    bool kept = false;
    int firstPass = -1, lastPass = -1;  // among live passes
    // Execution: an incoherent write not yet made visible for these uses.
    bool dirty = false;
    GLbitfield visibleBits = 0;
  };
  struct Access {
    uint32_t resource;
    uint32_t version;
    bool write;
    Usage usage;
  };
  struct Pass {
    std::string name;
    Execute execute;
    std::vector<Access> accesses;
    std::vector<uint32_t> creates;
    bool sideEffect = false;
    bool alive = false;
  };
  uint32_t addResource(Resource r);
  // A resource pass `pass` creates.
  uint32_t addCreated(uint32_t pass, Resource r);
  // A resource that exists before the frame (imported or persistent).
  uint32_t addExisting(Resource r, GLuint id);
  uint32_t beginPass(const std::string& name);
  void cull();
  GLbitfield placeBarriers(const Pass& pass);

  ResourcePool& pool_;
  std::vector<Resource> resources_;
  std::vector<Pass> passes_;
  std::vector<PassRecord> records_;
  std::vector<std::string> staleReads_;
};

}  // namespace hs::render
