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
// read stay alive, whatever order they were added in.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "render/resource_pool.h"

namespace hs::render {

struct TextureRef {
  uint32_t index = UINT32_MAX;
  bool valid() const { return index != UINT32_MAX; }
};
struct BufferRef {
  uint32_t index = UINT32_MAX;
  bool valid() const { return index != UINT32_MAX; }
};

class FrameGraph;

// Given to a pass's setup: what it uses.
class PassBuilder {
 public:
  TextureRef create(const std::string& name, const TextureDesc& desc);
  BufferRef create(const std::string& name, const BufferDesc& desc);
  // A buffer whose size an earlier pass of the same frame decides (the
  // A-buffer's node pool, sized by its counting pass): `desc` is asked when
  // the buffer's first pass is about to run, after every pass before it ran.
  BufferRef createSized(const std::string& name, std::function<BufferDesc()> desc);
  TextureRef read(TextureRef t);
  TextureRef write(TextureRef t);
  BufferRef read(BufferRef b);
  BufferRef write(BufferRef b);
  // The pass changes something outside the graph (the caller's framebuffer,
  // a readback, a query): it always runs.
  void sideEffect();

 private:
  friend class FrameGraph;
  PassBuilder(FrameGraph& g, uint32_t pass) : graph_(g), pass_(pass) {}
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
  // A framebuffer with these attachments (cached by the pool).
  GLuint framebuffer(const std::vector<TextureRef>& colors, TextureRef depth = {}, int layer = -1) const;

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
  double gpuMs = -1.0;    // from timestamp queries, when measured
  size_t gpuBytes = 0;    // transient resources first used by this pass
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

  // Culls and runs every needed pass in the order they were added.
  // `timestamps` wraps each pass in GPU timestamp queries, fenced with
  // glFinish on both sides so the interval is the pass's own work on any
  // driver, and waits for them at the end (for --stats, the editor's
  // per-pass list one frame in 30, and benchmarks; it serialises the frame).
  void execute(bool timestamps = false);

  const std::vector<PassRecord>& records() const { return records_; }
  // Texture of a kept resource after execute (0 if it was never made).
  GLuint keptTexture(TextureRef t) const;
  // Returns kept resources to the pool and forgets the frame.
  void reset();
  ~FrameGraph() { reset(); }

 private:
  friend class PassBuilder;
  friend class PassResources;
  struct Resource {
    std::string name;
    bool texture = true;
    TextureDesc tdesc;
    BufferDesc bdesc;
    std::function<BufferDesc()> lateDesc;  // createSized: asked at allocation
    GLuint imported = 0;   // nonzero: made elsewhere
    GLuint id = 0;         // while allocated
    uint32_t version = 0;  // current version during setup
    bool kept = false;
    int firstPass = -1, lastPass = -1;  // among live passes
  };
  struct Access {
    uint32_t resource;
    uint32_t version;
    bool write;
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
  uint32_t beginPass(const std::string& name);
  void cull();

  ResourcePool& pool_;
  std::vector<Resource> resources_;
  std::vector<Pass> passes_;
  std::vector<PassRecord> records_;
};

}  // namespace hs::render
