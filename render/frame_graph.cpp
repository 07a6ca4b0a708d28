#include "render/frame_graph.h"

#include <chrono>
#include <map>
#include <utility>

#include "render/gl/gl_handle.h"

namespace hs::render {

TextureRef PassBuilder::create(const std::string& name, const TextureDesc& desc) {
  FrameGraph::Resource r;
  r.name = name;
  r.texture = true;
  r.tdesc = desc;
  const uint32_t i = graph_.addResource(std::move(r));
  graph_.passes_[pass_].creates.push_back(i);
  return write(TextureRef{i});
}

BufferRef PassBuilder::create(const std::string& name, const BufferDesc& desc) {
  FrameGraph::Resource r;
  r.name = name;
  r.texture = false;
  r.bdesc = desc;
  const uint32_t i = graph_.addResource(std::move(r));
  graph_.passes_[pass_].creates.push_back(i);
  return write(BufferRef{i});
}

BufferRef PassBuilder::createSized(const std::string& name, std::function<BufferDesc()> desc) {
  FrameGraph::Resource r;
  r.name = name;
  r.texture = false;
  r.lateDesc = std::move(desc);
  const uint32_t i = graph_.addResource(std::move(r));
  graph_.passes_[pass_].creates.push_back(i);
  return write(BufferRef{i});
}

TextureRef PassBuilder::read(TextureRef t) {
  graph_.passes_[pass_].accesses.push_back({t.index, graph_.resources_[t.index].version, false});
  return t;
}

TextureRef PassBuilder::write(TextureRef t) {
  auto& r = graph_.resources_[t.index];
  graph_.passes_[pass_].accesses.push_back({t.index, ++r.version, true});
  return t;
}

BufferRef PassBuilder::read(BufferRef b) {
  graph_.passes_[pass_].accesses.push_back({b.index, graph_.resources_[b.index].version, false});
  return b;
}

BufferRef PassBuilder::write(BufferRef b) {
  auto& r = graph_.resources_[b.index];
  graph_.passes_[pass_].accesses.push_back({b.index, ++r.version, true});
  return b;
}

void PassBuilder::sideEffect() { graph_.passes_[pass_].sideEffect = true; }

GLuint PassResources::texture(TextureRef t) const { return graph_.resources_[t.index].id; }
GLuint PassResources::buffer(BufferRef b) const { return graph_.resources_[b.index].id; }
const TextureDesc& PassResources::desc(TextureRef t) const { return graph_.resources_[t.index].tdesc; }
const BufferDesc& PassResources::desc(BufferRef b) const { return graph_.resources_[b.index].bdesc; }

GLuint PassResources::framebuffer(const std::vector<TextureRef>& colors, TextureRef depth, int layer) const {
  std::vector<GLuint> ids;
  for (TextureRef c : colors) ids.push_back(texture(c));
  return graph_.pool_.framebuffer(ids, depth.valid() ? texture(depth) : 0, layer);
}

uint32_t FrameGraph::addResource(Resource r) {
  resources_.push_back(std::move(r));
  return uint32_t(resources_.size() - 1);
}

TextureRef FrameGraph::importTexture(const std::string& name, GLuint texture, const TextureDesc& desc) {
  Resource r;
  r.name = name;
  r.texture = true;
  r.tdesc = desc;
  r.imported = texture;
  r.id = texture;  // known from the start: keptTexture finds it even when no pass touches it
  r.version = 1;  // its content exists before the frame
  return TextureRef{addResource(std::move(r))};
}

BufferRef FrameGraph::importBuffer(const std::string& name, GLuint buffer, const BufferDesc& desc) {
  Resource r;
  r.name = name;
  r.texture = false;
  r.bdesc = desc;
  r.imported = buffer;
  r.version = 1;
  return BufferRef{addResource(std::move(r))};
}

uint32_t FrameGraph::beginPass(const std::string& name) {
  passes_.push_back(Pass{name, {}, {}, {}, false, false});
  return uint32_t(passes_.size() - 1);
}

void FrameGraph::keep(TextureRef t) { resources_[t.index].kept = true; }

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
      rec.gpuBytes += r.texture ? r.tdesc.bytes() : r.bdesc.bytes;
    }
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

void FrameGraph::reset() {
  for (Resource& r : resources_)
    if (r.id && !r.imported) {
      if (r.texture) pool_.releaseTexture(r.id);
      else pool_.releaseBuffer(r.id);
      r.id = 0;
    }
  resources_.clear();
  passes_.clear();
}

}  // namespace hs::render
