#include "render/frame_graph.h"

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <utility>

#include "render/gl/gl_handle.h"

namespace hs::render {
namespace {

int strictSetting() {
  if (const char* e = std::getenv("HS_FRAME_GRAPH_STRICT")) return e[0] == '1' ? 1 : 0;
#ifdef NDEBUG
  return 0;
#else
  return 1;
#endif
}
std::atomic<int> gStrict{-1};  // -1: not decided yet

}  // namespace

void FrameGraph::setStrictVersions(bool on) { gStrict = on ? 1 : 0; }
bool FrameGraph::strictVersions() {
  if (gStrict < 0) gStrict = strictSetting();
  return gStrict == 1;
}

GLbitfield barrierBitsFor(Usage u, bool texture) {
  GLbitfield bits = 0;
  if (any(u, Usage::RenderTarget)) bits |= GL_FRAMEBUFFER_BARRIER_BIT;
  if (any(u, Usage::Sampled)) bits |= GL_TEXTURE_FETCH_BARRIER_BIT;  // textures and texture buffers
  if (any(u, Usage::Storage))
    bits |= texture ? GL_SHADER_IMAGE_ACCESS_BARRIER_BIT
                    : GL_SHADER_STORAGE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT;
  if (any(u, Usage::Indirect)) bits |= GL_COMMAND_BARRIER_BIT;
  if (any(u, Usage::Vertex)) bits |= GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT;
  if (any(u, Usage::Uniform)) bits |= GL_UNIFORM_BARRIER_BIT;
  if (any(u, Usage::Readback))
    bits |= texture ? GL_TEXTURE_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT
                    : GL_BUFFER_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT;
  if (any(u, Usage::Transfer))
    bits |= texture ? GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT : GL_BUFFER_UPDATE_BARRIER_BIT;
  return bits;
}

TextureRef PassBuilder::create(const std::string& name, const TextureDesc& desc, Usage usage) {
  FrameGraph::Resource r;
  r.name = name;
  r.texture = true;
  r.tdesc = desc;
  return write(TextureRef{graph_.addCreated(pass_, std::move(r)), 0}, usage);
}

BufferRef PassBuilder::create(const std::string& name, const BufferDesc& desc, Usage usage) {
  FrameGraph::Resource r;
  r.name = name;
  r.texture = false;
  r.bdesc = desc;
  return write(BufferRef{graph_.addCreated(pass_, std::move(r)), 0}, usage);
}

BufferRef PassBuilder::createSized(const std::string& name, std::function<BufferDesc()> desc, Usage usage) {
  FrameGraph::Resource r;
  r.name = name;
  r.texture = false;
  r.lateDesc = std::move(desc);
  return write(BufferRef{graph_.addCreated(pass_, std::move(r)), 0}, usage);
}

uint32_t PassBuilder::access(uint32_t index, uint32_t version, bool write, Usage usage) {
  FrameGraph::Resource& r = graph_.resources_[index];
  if (write) {
    ++r.version;
  } else if (version != 0 && version != r.version) {
    // Reading through a reference a later write replaced.
    const std::string what = "frame graph: pass '" + graph_.passes_[pass_].name + "' uses version " +
                             std::to_string(version) + " of " + (r.texture ? "texture '" : "buffer '") + r.name +
                             "', which a later write replaced (now version " + std::to_string(r.version) + ")";
    if (FrameGraph::strictVersions()) throw std::logic_error(what);
    graph_.staleReads_.push_back(what);
  }
  graph_.passes_[pass_].accesses.push_back({index, r.version, write, usage});
  return r.version;
}

TextureRef PassBuilder::read(TextureRef t, Usage usage) { return {t.index, access(t.index, t.version, false, usage)}; }
TextureRef PassBuilder::write(TextureRef t, Usage usage) { return {t.index, access(t.index, t.version, true, usage)}; }
BufferRef PassBuilder::read(BufferRef b, Usage usage) { return {b.index, access(b.index, b.version, false, usage)}; }
BufferRef PassBuilder::write(BufferRef b, Usage usage) { return {b.index, access(b.index, b.version, true, usage)}; }

void PassBuilder::sideEffect() { graph_.passes_[pass_].sideEffect = true; }

GLuint PassResources::texture(TextureRef t) const { return graph_.resources_[t.index].id; }
GLuint PassResources::buffer(BufferRef b) const { return graph_.resources_[b.index].id; }
const TextureDesc& PassResources::desc(TextureRef t) const { return graph_.resources_[t.index].tdesc; }
const BufferDesc& PassResources::desc(BufferRef b) const { return graph_.resources_[b.index].bdesc; }
bool PassResources::fresh(TextureRef t) const { return graph_.resources_[t.index].fresh; }
bool PassResources::fresh(BufferRef b) const { return graph_.resources_[b.index].fresh; }

GLuint PassResources::framebuffer(const std::vector<TextureRef>& colors, TextureRef depth, int layer, int level) const {
  std::vector<GLuint> ids;
  for (TextureRef c : colors) ids.push_back(texture(c));
  return graph_.pool_.framebuffer(ids, depth.valid() ? texture(depth) : 0, layer, level);
}

GLuint PassResources::sampler(const SamplerDesc& s) const { return graph_.pool_.sampler(s); }

uint32_t FrameGraph::addResource(Resource r) {
  resources_.push_back(std::move(r));
  return uint32_t(resources_.size() - 1);
}

uint32_t FrameGraph::addCreated(uint32_t pass, Resource r) {
  const uint32_t i = addResource(std::move(r));
  passes_[pass].creates.push_back(i);
  return i;
}

uint32_t FrameGraph::addExisting(Resource r, GLuint id) {
  r.imported = id;
  r.id = id;      // known from the start: keptTexture finds it even when no pass touches it
  r.version = 1;  // its content exists before the frame (a persistent one's: last frame's)
  return addResource(std::move(r));
}

TextureRef FrameGraph::importTexture(const std::string& name, GLuint texture, const TextureDesc& desc) {
  Resource r;
  r.name = name;
  r.texture = true;
  r.tdesc = desc;
  return TextureRef{addExisting(std::move(r), texture), 1};
}

BufferRef FrameGraph::importBuffer(const std::string& name, GLuint buffer, const BufferDesc& desc) {
  Resource r;
  r.name = name;
  r.texture = false;
  r.bdesc = desc;
  return BufferRef{addExisting(std::move(r), buffer), 1};
}

TextureRef FrameGraph::persistentTexture(const std::string& name, const TextureDesc& desc, int lifetimeFrames) {
  Resource r;
  r.name = name;
  r.texture = true;
  r.tdesc = desc;
  r.persistent = true;
  const GLuint id = pool_.namedTexture(name, desc, lifetimeFrames, &r.fresh);
  return TextureRef{addExisting(std::move(r), id), 1};
}

BufferRef FrameGraph::persistentBuffer(const std::string& name, const BufferDesc& desc, int lifetimeFrames) {
  Resource r;
  r.name = name;
  r.texture = false;
  r.bdesc = desc;
  r.persistent = true;
  const GLuint id = pool_.namedBuffer(name, desc, lifetimeFrames, &r.fresh);
  return BufferRef{addExisting(std::move(r), id), 1};
}

void FrameGraph::readback(const std::string& name, BufferRef b, size_t offset, size_t bytes,
                          std::function<void(const void*, size_t)> deliver) {
  struct Data {
    BufferRef b;
  };
  addPass<Data>(
      name,
      [&](PassBuilder& pb, Data& d) {
        d.b = pb.read(b, Usage::Readback);
        pb.sideEffect();
      },
      [this, offset, bytes, deliver = std::move(deliver)](const Data& d, const PassResources& r) {
        pool_.queueReadback(r.buffer(d.b), offset, bytes, deliver);
      });
}

uint32_t FrameGraph::beginPass(const std::string& name) {
  passes_.push_back(Pass{name, {}, {}, {}, false, false});
  return uint32_t(passes_.size() - 1);
}

void FrameGraph::keep(TextureRef t) { resources_[t.index].kept = true; }
void FrameGraph::keep(BufferRef b) { resources_[b.index].kept = true; }

GLbitfield FrameGraph::placeBarriers(const Pass& pass) {
  GLbitfield bits = 0;
  for (const Access& a : pass.accesses) {
    const Resource& r = resources_[a.resource];
    if (r.dirty) bits |= barrierBitsFor(a.usage, r.texture) & ~r.visibleBits;
  }
  if (bits) {
    glMemoryBarrier(bits);
    // One barrier covers every earlier write, whichever resource it went to.
    for (Resource& r : resources_)
      if (r.dirty) r.visibleBits |= bits;
  }
  // This pass's own incoherent writes need a barrier before their next use.
  for (const Access& a : pass.accesses)
    if (a.write && any(a.usage, Usage::Storage)) {
      resources_[a.resource].dirty = true;
      resources_[a.resource].visibleBits = 0;
    }
  return bits;
}

void FrameGraph::cull() {
  // Who wrote each version.
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> producer;
  for (uint32_t p = 0; p < passes_.size(); ++p)
    for (const Access& a : passes_[p].accesses)
      if (a.write) producer[{a.resource, a.version}] = p;
  std::vector<uint32_t> work;
  auto live = [&](uint32_t p) {
    if (!passes_[p].alive) {
      passes_[p].alive = true;
      work.push_back(p);
    }
  };
  for (uint32_t p = 0; p < passes_.size(); ++p)
    if (passes_[p].sideEffect) live(p);
  for (uint32_t r = 0; r < resources_.size(); ++r)
    if (resources_[r].kept)
      if (auto it = producer.find({r, resources_[r].version}); it != producer.end()) live(it->second);
  while (!work.empty()) {
    const uint32_t p = work.back();
    work.pop_back();
    for (const Access& a : passes_[p].accesses)
      if (!a.write)
        if (auto it = producer.find({a.resource, a.version}); it != producer.end()) live(it->second);
  }
  for (uint32_t p = 0; p < passes_.size(); ++p) {
    if (!passes_[p].alive) continue;
    for (const Access& a : passes_[p].accesses) {
      Resource& r = resources_[a.resource];
      if (r.firstPass < 0) r.firstPass = int(p);
      r.lastPass = int(p);
    }
  }
}

void FrameGraph::execute(bool timestamps) {
  cull();
  // A persistent resource may hold an incoherent write from the last frame:
  // its first use here gets a barrier.
  for (Resource& r : resources_)
    if (r.persistent) r.dirty = true;
  records_.clear();
  std::vector<std::pair<gl::Query, gl::Query>> queries;
  for (uint32_t p = 0; p < passes_.size(); ++p) {
    Pass& pass = passes_[p];
    PassRecord rec;
    rec.name = pass.name;
    rec.ran = pass.alive;
    if (!pass.alive) {
      records_.push_back(rec);
      continue;
    }
    // Allocate what starts here.
    for (uint32_t i = 0; i < resources_.size(); ++i) {
      Resource& r = resources_[i];
      if (r.firstPass != int(p)) continue;
      if (r.imported) {
        r.id = r.imported;
        continue;
      }
      if (r.lateDesc) r.bdesc = r.lateDesc();
      r.id = r.texture ? pool_.acquireTexture(r.tdesc, r.name) : pool_.acquireBuffer(r.bdesc, r.name);
      rec.gpuBytes += r.texture ? r.tdesc.bytes() : bufferSizeClass(r.bdesc.bytes);
    }
    rec.barriers = placeBarriers(pass);
    // With timestamps each pass is fenced on both sides, and so is each
    // timestamp: drivers that run GL work when they flush (llvmpipe does)
    // would otherwise put one pass's work between another's timestamps, and
    // llvmpipe stamps a timestamp when its rasteriser threads reach it in
    // their tiles, so one queued with the pass's draws read as the end of
    // their work (the terrain pass got 0.9 of its 550 ms;
    // test_frame_graph::timedPassesReportTheirOwnWork). It serialises the
    // frame, which is why timings are asked for, not always on.
    if (timestamps) {
      glFinish();
      queries.emplace_back(gl::createQuery(GL_TIMESTAMP), gl::createQuery(GL_TIMESTAMP));
      glQueryCounter(queries.back().first.id(), GL_TIMESTAMP);
      glFinish();
    }
    const auto t0 = std::chrono::steady_clock::now();
    pass.execute(PassResources(*this));
    rec.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (timestamps) {
      glFinish();
      glQueryCounter(queries.back().second.id(), GL_TIMESTAMP);
      glFinish();  // stamped now, not with the next pass's allocations
    }
    records_.push_back(rec);
    // Return what ends here (kept resources stay for the caller).
    for (Resource& r : resources_)
      if (r.lastPass == int(p) && !r.imported && !r.kept && r.id) {
        if (r.texture) pool_.releaseTexture(r.id);
        else pool_.releaseBuffer(r.id);
        r.id = 0;
      }
  }
  if (timestamps) {
    size_t q = 0;
    for (PassRecord& rec : records_) {
      if (!rec.ran) continue;
      GLuint64 a = 0, b = 0;
      glGetQueryObjectui64v(queries[q].first.id(), GL_QUERY_RESULT, &a);
      glGetQueryObjectui64v(queries[q].second.id(), GL_QUERY_RESULT, &b);
      rec.gpuMs = double(b - a) * 1e-6;
      ++q;
    }
  }
}

GLuint FrameGraph::keptTexture(TextureRef t) const { return t.valid() ? resources_[t.index].id : 0; }
GLuint FrameGraph::keptBuffer(BufferRef b) const { return b.valid() ? resources_[b.index].id : 0; }

void FrameGraph::reset() {
  for (Resource& r : resources_)
    if (r.id && !r.imported) {
      if (r.texture) pool_.releaseTexture(r.id);
      else pool_.releaseBuffer(r.id);
      r.id = 0;
    }
  resources_.clear();
  passes_.clear();
  staleReads_.clear();
}

}  // namespace hs::render
