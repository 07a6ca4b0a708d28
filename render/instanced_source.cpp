#include "render/instanced_source.h"

#include <algorithm>
#include <cmath>

#include "render/frame_context.h"
#include "render/gpu_mesh_cache.h"
#include "render/material_binding.h"
#include "render/material_table.h"

namespace hs::render {
namespace {

// Storage bindings of shaders/instances.glsl and the culling shaders.
constexpr unsigned kInstanceBinding = 17, kCellBinding = 18, kVisibleBinding = 19;
constexpr unsigned kCullBinding0 = 20, kCullBinding1 = 21, kCountsBinding = 22, kTypeBaseBinding = 23;
constexpr size_t kCommandBytes = 5 * sizeof(uint32_t);  // DrawElementsIndirectCommand

uint32_t packSnorm2x16(float a, float b) {
  auto one = [](float v) { return uint32_t(uint16_t(int16_t(std::lround(std::clamp(v, -1.0f, 1.0f) * 32767.0f)))); };
  return one(a) | one(b) << 16;
}

float unpackSnorm16(uint32_t bits) { return std::max(float(int16_t(uint16_t(bits))) / 32767.0f, -1.0f); }

// A view's planes relative to the frame origin (Frustum planes are relative
// to their view's eye, `eyeRel` from the origin). A plane with no normal (an
// infinite far plane) never culls.
void appendPlanes(const Frustum& f, const glm::dvec3& eyeRel, std::vector<glm::vec4>& out) {
  for (const glm::dvec4& p : f.planes) {
    const glm::dvec3 n(p);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.w) ||
        glm::length(n) < 0.5) {
      out.emplace_back(0.0f, 0.0f, 0.0f, 1.0f);
      continue;
    }
    out.emplace_back(glm::vec3(n), float(p.w - glm::dot(n, eyeRel)));
  }
}

template <class T>
void upload(GLuint buffer, const std::vector<T>& data) {
  if (!data.empty()) glNamedBufferSubData(buffer, 0, GLsizeiptr(data.size() * sizeof(T)), data.data());
}

}  // namespace

GpuInstance packInstance(const glm::vec3& positionInCell, const glm::quat& rotation, float scale, uint16_t type,
                         uint16_t cell, uint32_t id) {
  const glm::quat q = glm::normalize(rotation);
  GpuInstance g;
  g.position = positionInCell;
  g.scale = scale;
  g.rotation[0] = packSnorm2x16(q.x, q.y);
  g.rotation[1] = packSnorm2x16(q.z, q.w);
  g.typeAndCell = uint32_t(type) | uint32_t(cell) << 16;
  g.id = id;
  return g;
}

glm::quat instanceRotation(const GpuInstance& g) {
  return glm::normalize(glm::quat(unpackSnorm16(g.rotation[1] >> 16), unpackSnorm16(g.rotation[0]),
                                  unpackSnorm16(g.rotation[0] >> 16), unpackSnorm16(g.rotation[1])));
}

InstancedSource::InstancedSource(std::string name, Culling culling) : name_(std::move(name)), culling_(culling) {
  // Its instance buffer's name in the pool: its own, so two sources of one
  // name (the same field culled two ways) never take each other's data.
  static uint64_t serial = 0;
  bufferName_ = name_ + "_instances#" + std::to_string(++serial);
}
InstancedSource::~InstancedSource() = default;

void InstancedSource::setInstances(InstanceSet set) {
  set_ = std::move(set);
  maxId_ = 0;
  for (const GpuInstance& g : set_.instances) maxId_ = std::max(maxId_, g.id);
  ++revision_;
}

bool InstancedSource::wanted(const Part& part, SurfaceSet surfaces) const {
  if (surfaces == SurfaceSet::All) return true;
  return materials_->forDraw(materialDraw_[part.type], part.submesh).translucent == (surfaces == SurfaceSet::Translucent);
}

bool InstancedSource::has(DrawVariant variant, SurfaceSet surfaces) const {
  if (!active_) return false;
  if (variant != DrawVariant::Surface) return true;
  return std::any_of(parts_.begin(), parts_.end(), [&](const Part& p) { return wanted(p, surfaces); });
}

void InstancedSource::addMaterials(FrameContext& frame, std::vector<DrawItem>& draws) {
  active_ = false;
  parts_.clear();
  meshes_.assign(set_.types.size(), nullptr);
  materialDraw_.assign(set_.types.size(), 0);
  if (set_.instances.empty() || !frame.world.state) return;
  for (size_t t = 0; t < set_.types.size(); ++t) {
    const scene::MeshAsset* asset = frame.world.state->findAsset(set_.types[t]);
    const GpuMesh* mesh = asset ? frame.res.meshes.get(*asset) : nullptr;
    if (!mesh) continue;  // a type whose asset is gone draws nothing
    meshes_[t] = mesh;
    materialDraw_[t] = draws.size();
    draws.push_back({0, mesh, asset});
    const auto& subs = mesh->data->submeshes;
    for (size_t s = 0; s < subs.size(); ++s)
      parts_.push_back({uint32_t(t), subs[s].firstIndex, subs[s].indexCount, uint32_t(s)});
  }
  materials_ = &frame.res.materials;
  active_ = !parts_.empty();
}

void InstancedSource::addPreparePasses(FrameGraph& graph, FrameContext& frame) {
  if (!active_) return;
  const size_t n = set_.instances.size(), types = set_.types.size();
  cameraViews_ = frame.views ? frame.views->size() : 0;
  const size_t views = cameraViews_ + frame.shadowViews.size();
  // Each type's first slot in a view's list (a view's list holds every instance at most once).
  typeBase_.assign(types, 0);
  std::vector<uint32_t> perType(types, 0);
  for (const GpuInstance& g : set_.instances) ++perType[std::min<size_t>(g.typeAndCell & 0xFFFFu, types - 1)];
  for (size_t t = 1; t < types; ++t) typeBase_[t] = typeBase_[t - 1] + perType[t - 1];
  std::vector<glm::vec4> planes;
  for (size_t v = 0; v < cameraViews_; ++v)
    appendPlanes(frustumOf((*frame.views)[v]), (*frame.views)[v].eye - frame.visible.origin, planes);
  for (const Frustum& f : frame.shadowViews) appendPlanes(f, glm::dvec3(0.0), planes);
  std::vector<glm::vec4> cells;
  for (const glm::dvec3& c : set_.cells) cells.emplace_back(glm::vec3(c - frame.visible.origin), 0.0f);
  if (cells.empty()) cells.emplace_back(0.0f);
  // The types' bounding spheres in mesh space.
  std::vector<glm::vec4> spheres(types, glm::vec4(0.0f, 0.0f, 0.0f, -1.0f));
  for (size_t t = 0; t < types; ++t)
    if (meshes_[t]) spheres[t] = glm::vec4(meshes_[t]->bounds.center(), meshes_[t]->bounds.radius());

  const bool gpu = culling_ == Culling::Gpu;
  std::vector<uint32_t> cpuVisible;
  if (!gpu) {
    // The same test as shaders/instance_cull.comp, in double, each list in
    // instance order.
    cpuCounts_.assign(views * types, 0);
    cpuVisible.assign(views * n, 0);
    for (size_t i = 0; i < n; ++i) {
      const GpuInstance& g = set_.instances[i];
      const size_t type = g.typeAndCell & 0xFFFFu, cell = g.typeAndCell >> 16;
      if (type >= types || spheres[type].w < 0.0f || cell >= cells.size()) continue;
      const glm::dmat3 rot = glm::mat3_cast(glm::dquat(instanceRotation(g)));
      const glm::dvec3 centre = glm::dvec3(cells[cell]) + glm::dvec3(g.position) +
                                rot * (glm::dvec3(spheres[type]) * double(g.scale));
      const double radius = double(spheres[type].w) * std::abs(double(g.scale));
      for (size_t v = 0; v < views; ++v) {
        bool inside = true;
        for (size_t k = 0; k < 6 && inside; ++k) {
          const glm::dvec4 p(planes[v * 6 + k]);
          inside = glm::dot(glm::dvec3(p), centre) + p.w >= -radius;
        }
        if (inside) cpuVisible[v * n + typeBase_[type] + cpuCounts_[v * types + type]++] = uint32_t(i);
      }
    }
    int64_t seen = 0;
    for (size_t v = 0; v < cameraViews_; ++v)
      for (size_t t = 0; t < types; ++t) seen += cpuCounts_[v * types + t];
    *lastVisible_ = seen;
  }

  struct Upload {
    BufferRef instances, cells, visible;
  };
  const size_t visibleBytes = std::max<size_t>(cpuVisible.size(), 1) * 4;  // before the execute takes the list
  const Upload& up = graph.addPass<Upload>(
      name_ + "_upload",
      [&](PassBuilder& b, Upload& d) {
        d.instances = b.write(graph.persistentBuffer(bufferName_, BufferDesc{n * sizeof(GpuInstance)}),
                              Usage::Transfer);
        d.cells = b.create(name_ + "_cells", BufferDesc{cells.size() * sizeof(glm::vec4)}, Usage::Transfer);
        if (!gpu) d.visible = b.create(name_ + "_visible", BufferDesc{visibleBytes}, Usage::Transfer);
      },
      [this, cells, cpuVisible = std::move(cpuVisible)](const Upload& d, const PassResources& r) {
        if (r.fresh(d.instances) || uploaded_ != revision_) {
          upload(r.buffer(d.instances), set_.instances);
          uploaded_ = revision_;
        }
        upload(r.buffer(d.cells), cells);
        if (d.visible.valid()) upload(r.buffer(d.visible), cpuVisible);
      });
  instanceBuffer_ = up.instances;
  cells_ = up.cells;
  visible_ = up.visible;
  commands_ = {};
  if (!gpu) return;

  // The GPU's culling and its commands (one per view and part).
  std::vector<glm::uvec4> parts;
  for (const Part& p : parts_) parts.emplace_back(p.indexCount, p.firstIndex, p.type, 0u);
  struct Cull {
    BufferRef instances, cells, visible, counts, commands, spheres, planes, typeBase, parts;
  };
  const Cull& cull = graph.addPass<Cull>(
      name_ + "_cull",
      [&](PassBuilder& b, Cull& d) {
        d.instances = b.read(up.instances);
        d.cells = b.read(up.cells);
        d.visible = b.create(name_ + "_visible", BufferDesc{views * n * 4});
        d.counts = b.create(name_ + "_counts", BufferDesc{views * types * 4});
        d.commands = b.create(name_ + "_commands", BufferDesc{views * parts.size() * kCommandBytes});
        d.spheres = b.create(name_ + "_types", BufferDesc{spheres.size() * sizeof(glm::vec4)}, Usage::Transfer);
        d.planes = b.create(name_ + "_planes", BufferDesc{std::max<size_t>(planes.size(), 1) * sizeof(glm::vec4)},
                            Usage::Transfer);
        d.typeBase = b.create(name_ + "_type_base", BufferDesc{types * 4}, Usage::Transfer);
        d.parts = b.create(name_ + "_parts", BufferDesc{parts.size() * sizeof(glm::uvec4)}, Usage::Transfer);
      },
      [this, &frame, n, views, types, cellCount = cells.size(), spheres, planes, parts](const Cull& d,
                                                                                         const PassResources& r) {
        upload(r.buffer(d.spheres), spheres);
        upload(r.buffer(d.planes), planes);
        upload(r.buffer(d.typeBase), typeBase_);
        upload(r.buffer(d.parts), parts);
        const GLuint zero = 0;
        glClearNamedBufferData(r.buffer(d.counts), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInstanceBinding, r.buffer(d.instances));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCellBinding, r.buffer(d.cells));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVisibleBinding, r.buffer(d.visible));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullBinding0, r.buffer(d.spheres));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullBinding1, r.buffer(d.planes));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCountsBinding, r.buffer(d.counts));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTypeBaseBinding, r.buffer(d.typeBase));
        // Uploads and clears before the dispatch read them.
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        GlProgram& cullProgram = frame.res.program({"", "", "instance_cull.comp", {}});
        cullProgram.use();
        cullProgram.set("uInstances", unsigned(n));
        cullProgram.set("uViews", unsigned(views));
        cullProgram.set("uTypes", unsigned(types));
        cullProgram.set("uCells", unsigned(cellCount));
        glDispatchCompute(GLuint((n + 63) / 64), 1, 1);
        // Within the pass: the commands read the counts.
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        GlProgram& commands = frame.res.program({"", "", "instance_commands.comp", {}});
        commands.use();
        commands.set("uParts", unsigned(parts.size()));
        commands.set("uViews", unsigned(views));
        commands.set("uTypes", unsigned(types));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullBinding0, r.buffer(d.parts));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCullBinding1, r.buffer(d.commands));
        glDispatchCompute(GLuint((parts.size() * views + 63) / 64), 1, 1);
        // The passes that draw read the commands and lists: the graph's
        // barrier (Usage::Indirect and Storage reads of Storage writes).
      });
  visible_ = cull.visible;
  commands_ = cull.commands;
  // The visible counts, a frame or more later, for the statistics.
  graph.readback(name_ + "_counts", cull.counts, 0, views * types * 4,
                 [seen = lastVisible_, cameraViews = cameraViews_, types](const void* data, size_t) {
                   const auto* c = static_cast<const uint32_t*>(data);
                   int64_t sum = 0;
                   for (size_t i = 0; i < cameraViews * types; ++i) sum += c[i];
                   *seen = sum;
                 });
}

void InstancedSource::declare(PassBuilder& b, DrawVariant) const {
  if (!active_) return;
  b.read(instanceBuffer_);
  b.read(cells_);
  b.read(visible_);
  if (commands_.valid()) b.read(commands_, Usage::Indirect);
}

void InstancedSource::bindInstances(const PassResources& r) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInstanceBinding, r.buffer(instanceBuffer_));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCellBinding, r.buffer(cells_));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVisibleBinding, r.buffer(visible_));
  if (commands_.valid()) glBindBuffer(GL_DRAW_INDIRECT_BUFFER, r.buffer(commands_));
}

size_t InstancedSource::triangles(SurfaceSet surfaces) const {
  if (culling_ == Culling::Gpu || !active_) return 0;  // the GPU's counts come back later (lastVisible)
  size_t n = 0;
  const size_t types = set_.types.size();
  for (const Part& p : parts_)
    if (wanted(p, surfaces))
      for (size_t v = 0; v < cameraViews_; ++v) n += size_t(cpuCounts_[v * types + p.type]) * (p.indexCount / 3);
  return n;
}

// Draws view `view`'s visible instances of every wanted part: one program
// per material variant (or the pass's fragment), mesh.vert's INSTANCED.
void InstancedSource::drawParts(FrameContext& frame, const PassResources& r, size_t view, const DrawCall& call) {
  const size_t n = set_.instances.size(), types = set_.types.size();
  bindInstances(r);
  std::vector<std::string> defines = call.defines;
  defines.push_back("INSTANCED");
  MaterialBinding binding(frame, defines, call.fragment);
  for (size_t k = 0; k < parts_.size(); ++k) {
    const Part& part = parts_[k];
    if (call.variant == DrawVariant::Surface && !wanted(part, call.surfaces)) continue;
    const DrawMaterial& mat = materials_->forDraw(materialDraw_[part.type], part.submesh);
    GlProgram* p = nullptr;
    if (call.variant == DrawVariant::Pick) {
      p = &frame.res.program({"mesh.vert", "pick.frag", "", {"INSTANCED"}});
      p->use();
      p->set("uPickBase", call.pickBase);
    } else if (call.variant == DrawVariant::Depth) {
      p = &frame.res.program({"mesh.vert", "shadow_depth.frag", "",
                              mat.castsCutout ? std::vector<std::string>{"INSTANCED", "ALPHA_CUTOUT"}
                                              : std::vector<std::string>{"INSTANCED"}});
      p->use();
      if (mat.castsCutout) bindCutout(*p, mat);
    } else {
      p = &binding.apply(mat);
    }
    p->set("uInstanceBase", unsigned(view * n + typeBase_[part.type]));
    const GLuint vao = meshes_[part.type]->vao;
    glBindVertexArray(vao);
    // Attribute 7 is the document meshes' object index (divisor 1): off,
    // so no instance reads past its buffer.
    glDisableVertexArrayAttrib(vao, 7);
    const void* indices = reinterpret_cast<const void*>(uintptr_t(part.firstIndex) * sizeof(uint32_t));
    if (commands_.valid()) {
      glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                                  reinterpret_cast<const void*>((view * parts_.size() + k) * kCommandBytes), 1, 0);
      ++frame.stats.drawCalls;
    } else if (const uint32_t count = cpuCounts_[view * types + part.type]) {
      glDrawElementsInstanced(GL_TRIANGLES, GLsizei(part.indexCount), GL_UNSIGNED_INT, indices, GLsizei(count));
      ++frame.stats.drawCalls;
      if (call.variant == DrawVariant::Surface && call.surfaces == SurfaceSet::Opaque) {
        frame.stats.trianglesDrawn += size_t(count) * (part.indexCount / 3);
        frame.stats.instancesDrawn += count;
      }
    }
    glEnableVertexArrayAttrib(vao, 7);
  }
  binding.finish();
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

void InstancedSource::draw(FrameContext& frame, const DrawCall& call, const PassResources& r) {
  if (!active_) return;
  const size_t view = call.variant == DrawVariant::Depth ? cameraViews_ + call.shadowView : call.view;
  // The pick frame draws view 0 (its one view); shadow views follow the camera views.
  drawParts(frame, r, view, call);
}

}  // namespace hs::render
