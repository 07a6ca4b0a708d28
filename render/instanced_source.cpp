#include "render/instanced_source.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/packing.hpp>

#include "core/lowbias32.h"
#include "meshproc/lod_chain.h"
#include "render/frame_context.h"
#include "render/gpu_mesh_cache.h"
#include "render/impostor_atlas.h"
#include "render/impostor_cache.h"
#include "scene/impostor_key.h"
#include "render/material_binding.h"
#include "render/material_table.h"
#include "render/mesh_lod.h"
#include "render/render_resources.h"

namespace hs::render {
namespace {

// Storage bindings of shaders/instances.glsl, mesh.vert's INSTANCED
// variant and the culling shaders.
constexpr unsigned kInstanceBinding = 17, kCellBinding = 18, kVisibleBinding = 19;
constexpr unsigned kTypeCullBinding = 20, kPlanesBinding = 21, kCountsBinding = 22, kGroupBaseBinding = 23;
constexpr unsigned kLevelsBinding = 24, kGroupTotalsBinding = 25, kLodDistanceBinding = 26;
constexpr unsigned kPartsBinding = 20, kCommandsBinding = 21;  // instance_commands.comp's own
constexpr size_t kCommandBytes = 5 * sizeof(uint32_t);  // DrawElementsIndirectCommand
constexpr uint32_t kCulled = 0xFFFFFFFFu;               // an instance's level: no view draws it
// Beyond the cull distance by more than this share the culling passes drop
// an instance; closer, mesh.vert's fade (1 from the cull distance on)
// drops its pixels. So the image does not depend on whether the GPU's
// float and the CPU's double round a distance at the boundary alike.
constexpr float kCullSlack = 1.0f + 1e-5f;

// shaders/instances.glsl InstanceTypeCull, std430.
struct GpuTypeCull {
  glm::vec4 sphere{0.0f, 0.0f, 0.0f, -1.0f};  // level 0's bounds (mesh space); w < 0: draws nothing
  glm::vec4 cull{0.0f};                       // x: radius of every level, y: cull distance, z: wind margin per |scale z|
  glm::uvec4 info{0u};                        // x: first group, y: levels, z: casts shadows
};
static_assert(sizeof(GpuTypeCull) == 48);

uint32_t packSnorm2x16(float a, float b) {
  auto one = [](float v) { return uint32_t(uint16_t(int16_t(std::lround(std::clamp(v, -1.0f, 1.0f) * 32767.0f)))); };
  return one(a) | one(b) << 16;
}

float unpackSnorm16(uint32_t bits) { return std::max(float(int16_t(uint16_t(bits))) / 32767.0f, -1.0f); }

// The wind's phase per instance id, as shaders/instances.glsl hashes it.
uint32_t windHash(uint32_t h) { return lowbias32(h); }

// The largest |factor| of a scale, as chooseMeshLod and the sphere take it.
double maxAbsScale(const glm::vec3& s) { return std::max({std::abs(double(s.x)), std::abs(double(s.y)), std::abs(double(s.z))}); }

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

GpuInstance packInstance(const glm::vec3& positionInCell, const glm::quat& rotation, glm::vec2 scaleXyZ,
                         uint16_t type, uint16_t cell, uint32_t id) {
  const glm::quat q = glm::normalize(rotation);
  GpuInstance g;
  g.position = positionInCell;
  g.scaleXyZ = glm::packHalf2x16(scaleXyZ);
  g.rotation[0] = packSnorm2x16(q.x, q.y);
  g.rotation[1] = packSnorm2x16(q.z, q.w);
  g.typeAndCell = uint32_t(type) | uint32_t(cell) << 16;
  g.id = id;
  return g;
}

GpuInstance packInstance(const glm::vec3& positionInCell, const glm::quat& rotation, float scale, uint16_t type,
                         uint16_t cell, uint32_t id) {
  return packInstance(positionInCell, rotation, glm::vec2(scale), type, cell, id);
}

glm::quat instanceRotation(const GpuInstance& g) {
  return glm::normalize(glm::quat(unpackSnorm16(g.rotation[1] >> 16), unpackSnorm16(g.rotation[0]),
                                  unpackSnorm16(g.rotation[0] >> 16), unpackSnorm16(g.rotation[1])));
}

glm::vec3 instanceScale(const GpuInstance& g) {
  const glm::vec2 s = glm::unpackHalf2x16(g.scaleXyZ);
  return {s.x, s.x, s.y};
}

glm::vec3 instanceWindOffset(float response, float heightAboveOrigin, float meshHeight, float scaleZ, uint32_t id,
                             double seconds) {
  if (!(response > 0.0f) || !(meshHeight > 0.0f)) return glm::vec3(0.0f);
  constexpr float tau = 6.28318531f;
  const float h = std::clamp(heightAboveOrigin / meshHeight, 0.0f, 1.0f);
  const float worldHeight = meshHeight * std::abs(scaleZ);
  const float phase = tau * float(windHash(id) >> 8) * (1.0f / 16777216.0f);
  const float t = float(seconds - 60.0 * std::floor(seconds / 60.0));  // the shader's t mod 60 s
  auto wave = [&](float hz, float shift) { return std::sin(tau * (hz * t - std::floor(hz * t)) + shift); };
  const float bend = 0.6f + 0.4f * wave(0.5f, phase);
  const float gust = 0.3f * wave(1.3f, 1.7f * phase) * (0.5f + 0.5f * wave(0.2f, 0.5f * phase));
  const glm::vec2 across(-kWindDirection.y, kWindDirection.x);
  const glm::vec2 move = kWindBend * response * worldHeight * h * h * (kWindDirection * bend + across * gust);
  const float stem = h * worldHeight;
  const float drop = stem > 0.0f ? glm::dot(move, move) / (2.0f * stem) : 0.0f;
  return {move, -drop};
}

float instanceWindMargin(float response, float worldHeight) {
  if (!(response > 0.0f)) return 0.0f;
  // |move| <= a |(bend, gust)| <= a sqrt(1 + 0.3^2) with a = kWindBend x
  // response x height at the top (h = 1); the drop is |move|^2 / (2 h
  // height) <= (1.0441 a)^2 h^3 / (2 height) <= 0.5451 a^2 / height. One
  // per cent more for float rounding.
  const float a = kWindBend * response;
  return 1.01f * std::abs(worldHeight) * (1.0441f * a + 0.5451f * a * a);
}

InstancedSource::InstancedSource(std::string name, Culling culling) : name_(std::move(name)), culling_(culling) {
  // Its instance buffer's name in the pool: its own, so two sources of one
  // name (the same field culled two ways) never take each other's data.
  static uint64_t serial = 0;
  bufferName_ = name_ + "_instances#" + std::to_string(++serial);
}
InstancedSource::~InstancedSource() = default;

void InstancedSource::widen(const GpuInstance& g) {
  const size_t type = g.typeAndCell & 0xFFFFu, cell = g.typeAndCell >> 16;
  if (type >= minScale_.size()) return;  // a spare place (kSpareInstance)
  maxId_ = std::max(maxId_, g.id);
  const float scale = float(maxAbsScale(instanceScale(g)));
  minScale_[type] = std::min(minScale_[type], scale);
  maxScale_ = std::max(maxScale_, scale);
  if (cell >= cellBoxes_.size()) return;
  cellBoxes_[cell].first = glm::min(cellBoxes_[cell].first, g.position);
  cellBoxes_[cell].second = glm::max(cellBoxes_[cell].second, g.position);
}

void InstancedSource::setInstances(InstanceSet set) {
  set_ = std::move(set);
  maxId_ = 0;
  maxScale_ = 0.0f;
  minScale_.assign(set_.types.size(), std::numeric_limits<float>::infinity());
  cellBoxes_.assign(set_.cells.size(), {glm::vec3(std::numeric_limits<float>::infinity()),
                                        glm::vec3(-std::numeric_limits<float>::infinity())});
  for (const GpuInstance& g : set_.instances) widen(g);
  ++revision_;
  pending_.clear();
}

void InstancedSource::updateInstances(size_t first, const GpuInstance* items, size_t n) {
  if (n == 0 || first + n > set_.instances.size()) return;
  std::copy(items, items + n, set_.instances.begin() + std::ptrdiff_t(first));
  // The bounds only widen: an instance that left may have been the
  // smallest (a smaller minimum scale only lets the impostor start later),
  // or the nearest (a nearer bound only blurs less).
  for (size_t i = 0; i < n; ++i) widen(items[i]);
  pending_.emplace_back(first, n);
}

uint16_t InstancedSource::addCell(const glm::dvec3& origin) {
  set_.cells.push_back(origin);  // the cells go up every frame (small): nothing else to do
  cellBoxes_.push_back({glm::vec3(std::numeric_limits<float>::infinity()),
                        glm::vec3(-std::numeric_limits<float>::infinity())});
  return uint16_t(set_.cells.size() - 1);
}

double InstancedSource::nearestDepth(const RenderView& view) const {
  if (!active_) return INFINITY;
  double reach = 0.0;
  for (const TypeFrame& tf : types_)
    if (tf.asset)
      reach = std::max(reach, double(glm::length(glm::vec3(tf.lodSphere)) + tf.cullRadius + tf.windPerScaleZ));
  reach *= double(maxScale_);
  const glm::dvec3 fwd = view.forward();
  double nearest = INFINITY;
  for (size_t c = 0; c < cellBoxes_.size() && c < set_.cells.size(); ++c) {
    const auto& [lo, hi] = cellBoxes_[c];
    if (lo.x > hi.x) continue;
    const glm::dvec3 o = set_.cells[c] - view.eye;
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 p(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
      nearest = std::min(nearest, glm::dot(o + p, fwd));
    }
  }
  return nearest - reach;
}

bool InstancedSource::wanted(const Part& part, SurfaceSet surfaces) const {
  if (surfaces == SurfaceSet::All) return true;
  if (!groups_[part.group].mesh) return surfaces == SurfaceSet::Opaque;  // an impostor: cut out, opaque
  return materials_->forDraw(groups_[part.group].materialDraw, part.submesh).translucent ==
         (surfaces == SurfaceSet::Translucent);
}

bool InstancedSource::has(DrawVariant variant, SurfaceSet surfaces) const {
  if (!active_) return false;
  if (variant == DrawVariant::Depth) return anyCaster_;
  if (variant != DrawVariant::Surface) return true;
  return std::any_of(parts_.begin(), parts_.end(), [&](const Part& p) { return wanted(p, surfaces); });
}

void InstancedSource::addMaterials(FrameContext& frame, std::vector<DrawItem>& draws) {
  active_ = false;
  anyCaster_ = false;
  parts_.clear();
  groups_.clear();
  types_.assign(set_.types.size(), TypeFrame{});
  if (set_.instances.empty() || !frame.world.state) return;
  for (size_t t = 0; t < set_.types.size(); ++t) {
    TypeFrame& tf = types_[t];
    const scene::MeshAsset* asset = frame.world.state->findAsset(set_.types[t].mesh);
    const GpuMesh* base = asset ? frame.res.meshes.get(*asset) : nullptr;
    if (!base) continue;  // a type whose asset is gone draws nothing
    tf.asset = asset;
    tf.errors = asset->lodErrors();
    tf.firstGroup = uint32_t(groups_.size());
    tf.levels = uint32_t(tf.errors.size());
    const glm::vec3 centre = base->bounds.center();
    tf.lodSphere = glm::vec4(centre, base->bounds.radius());
    tf.height = base->bounds.empty ? 0.0f : std::max(base->bounds.max.z, 0.0f);
    tf.windPerScaleZ = instanceWindMargin(set_.types[t].windResponse, tf.height);
    anyCaster_ = anyCaster_ || set_.types[t].castShadows;
    for (uint32_t level = 0; level < tf.levels; ++level) {
      // Level 0's mesh where the cache has no such level (as the mesh source draws it).
      const GpuMesh* mesh = level == 0 ? base : frame.res.meshes.get(*asset, int(level));
      if (!mesh) mesh = base;
      // A sphere about level 0's centre that holds this level too.
      if (!mesh->bounds.empty)
        tf.cullRadius = std::max(tf.cullRadius, glm::length(mesh->bounds.center() - centre) + mesh->bounds.radius());
      const uint32_t group = uint32_t(groups_.size());
      groups_.push_back({uint32_t(t), level, mesh, draws.size()});
      draws.push_back({0, mesh, asset});
      const auto& subs = mesh->data->submeshes;
      for (size_t s = 0; s < subs.size(); ++s)
        parts_.push_back({group, uint32_t(t), subs[s].firstIndex, subs[s].indexCount, uint32_t(s)});
    }
    // The impostor after the mesh levels (instanced_source.h), where an
    // instance can reach it: from `reach` metres (the LOD rule's distance
    // for its error) at the type's smallest scale, within its cull distance.
    const InstanceType& type = set_.types[t];
    if (type.impostor && !base->bounds.empty && base->bounds.radius() > 0.0f) {
      const double error = std::max(impostorError(base->bounds.radius()), tf.errors.back());
      const double reach = mesh::lodDistance(error, frame.lodView.fovY, double(frame.lodView.height),
                                             frame.settings.meshLodErrorPixels) *
                           double(minScale_[t]);
      if (std::isfinite(reach) && (!(type.cullDistance > 0.0f) || reach < double(type.cullDistance))) {
        tf.errors.push_back(error);
        const auto& subs = base->data->submeshes;
        for (size_t s = 1; s < subs.size(); ++s)
          if (subs[s].indexCount > subs[tf.impostorSubmesh].indexCount) tf.impostorSubmesh = uint32_t(s);
        const uint32_t group = uint32_t(groups_.size());
        groups_.push_back({uint32_t(t), tf.levels, nullptr, groups_[tf.firstGroup].materialDraw});
        parts_.push_back({group, uint32_t(t), 0, 6, 0});  // the card: two triangles (ImpostorCache::cardVao)
        ++tf.levels;
        tf.hasImpostor = true;
      }
    }
    // Float rounding of a centre far from the mesh origin: a hair more.
    tf.cullRadius *= 1.0f + 1e-6f;
  }
  materials_ = &frame.res.materials;
  active_ = !parts_.empty();
  if (!active_) anyCaster_ = false;
}

void InstancedSource::addPreparePasses(FrameGraph& graph, FrameContext& frame) {
  if (!active_) return;
  // Atlases for the types that may draw an impostor (stored, or baked on first need;
  // the frame's material block is bound by now).
  for (size_t t = 0; t < types_.size(); ++t) {
    TypeFrame& tf = types_[t];
    if (!tf.hasImpostor) continue;
    const Group& level0 = groups_[tf.firstGroup];
    std::vector<DrawMaterial> materials;
    for (size_t s = 0; s < level0.mesh->data->submeshes.size(); ++s)
      materials.push_back(materials_->forDraw(level0.materialDraw, s));
    const scene::MeshAsset* asset = frame.world.state->findAsset(set_.types[t].mesh);
    if (!asset) continue;
    tf.impostor = frame.res.impostors.get(frame.res, *asset, scene::impostorSourceKey(*frame.world.state, *asset),
                                          *level0.mesh, materials);
  }
  const size_t n = set_.instances.size(), types = types_.size(), groups = groups_.size();
  cameraViews_ = frame.views ? frame.views->size() : 0;
  const size_t views = cameraViews_ + frame.shadowViews.size();
  std::vector<glm::vec4> planes;
  for (size_t v = 0; v < cameraViews_; ++v)
    appendPlanes(frustumOf((*frame.views)[v]), (*frame.views)[v].eye - frame.visible.origin, planes);
  for (const Frustum& f : frame.shadowViews) appendPlanes(f, glm::dvec3(0.0), planes);
  // A plane that never culls (0, 0, 0, 1) in every place: no view culling.
  if (!viewCulling_) planes.assign(views * 6, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  std::vector<glm::vec4> cells;
  for (const glm::dvec3& c : set_.cells) cells.emplace_back(glm::vec3(c - frame.visible.origin), 0.0f);
  if (cells.empty()) cells.emplace_back(0.0f);
  // The LOD view (mesh_lod.h): its eye relative to the frame origin, and
  // for each group the distance (in the mesh's own metres: divided by the
  // instance's largest scale) from which its level's error projects within
  // the pixel bound (mesh::lodDistance): the GPU compares, the CPU asks
  // chooseMeshLod itself.
  const RenderView& lodView = frame.lodView;
  const glm::dvec3 lodEyeD = lodView.eye - frame.visible.origin;
  lodEye_ = glm::vec3(lodEyeD);
  std::vector<float> lodDistances(groups, std::numeric_limits<float>::infinity());
  std::vector<GpuTypeCull> typeCull(types);
  for (size_t t = 0; t < types; ++t) {
    const TypeFrame& tf = types_[t];
    if (!tf.asset) continue;
    for (uint32_t l = 0; l < tf.levels; ++l)
      if (l == 0) lodDistances[tf.firstGroup] = 0.0f;
      else
        lodDistances[tf.firstGroup + l] = float(mesh::lodDistance(tf.errors[l], lodView.fovY, double(lodView.height),
                                                                  frame.settings.meshLodErrorPixels));
    typeCull[t].sphere = tf.lodSphere;
    typeCull[t].cull = glm::vec4(tf.cullRadius, set_.types[t].cullDistance, tf.windPerScaleZ, 0.0f);
    typeCull[t].info = glm::uvec4(tf.firstGroup, tf.levels, set_.types[t].castShadows ? 1u : 0u, 0u);
  }

  const bool gpu = culling_ == Culling::Gpu;
  std::vector<uint32_t> cpuVisible, cpuGroupBase;
  if (!gpu) {
    // The same choices as the compute passes, in double: the level by
    // chooseMeshLod (the mesh source's rule), the cull distance, then the
    // sphere test per view; each list in instance order.
    std::vector<uint32_t> level(n, kCulled), totals(groups, 0);
    for (size_t i = 0; i < n; ++i) {
      const GpuInstance& g = set_.instances[i];
      const size_t type = g.typeAndCell & 0xFFFFu, cell = g.typeAndCell >> 16;
      if (type >= types || !types_[type].asset || cell >= cells.size()) continue;
      const TypeFrame& tf = types_[type];
      const glm::dvec3 origin = glm::dvec3(cells[cell]) + glm::dvec3(g.position);
      const double cullDistance = set_.types[type].cullDistance;
      if (cullDistance > 0 && glm::length(origin - lodEyeD) > cullDistance * double(kCullSlack)) continue;
      const glm::dvec3 s(instanceScale(g));
      const glm::dvec3 centre = origin + glm::mat3_cast(glm::dquat(instanceRotation(g))) * (glm::dvec3(tf.lodSphere) * s);
      level[i] = uint32_t(chooseMeshLod(tf.errors, centre - lodEyeD, double(tf.lodSphere.w),
                                        maxAbsScale(glm::vec3(s)), lodView, frame.settings.meshLodErrorPixels)
                              .level);
      ++totals[tf.firstGroup + level[i]];
    }
    cpuGroupBase.assign(groups, 0);
    for (size_t k = 1; k < groups; ++k) cpuGroupBase[k] = cpuGroupBase[k - 1] + totals[k - 1];
    cpuCounts_.assign(views * groups, 0);
    cpuVisible.assign(views * n, 0);
    for (size_t i = 0; i < n; ++i) {
      if (level[i] == kCulled) continue;
      const GpuInstance& g = set_.instances[i];
      const size_t type = g.typeAndCell & 0xFFFFu, cell = g.typeAndCell >> 16;
      const TypeFrame& tf = types_[type];
      const size_t group = tf.firstGroup + level[i];
      const glm::dvec3 s(instanceScale(g));
      const glm::dvec3 centre = glm::dvec3(cells[cell]) + glm::dvec3(g.position) +
                                glm::mat3_cast(glm::dquat(instanceRotation(g))) * (glm::dvec3(tf.lodSphere) * s);
      const double radius = double(tf.cullRadius) * maxAbsScale(glm::vec3(s)) + double(tf.windPerScaleZ) * std::abs(s.z);
      const size_t casting = set_.types[type].castShadows ? views : cameraViews_;
      for (size_t v = 0; v < casting; ++v) {
        bool inside = true;
        for (size_t k = 0; k < 6 && inside; ++k) {
          const glm::dvec4 p(planes[v * 6 + k]);
          inside = glm::dot(glm::dvec3(p), centre) + p.w >= -radius;
        }
        if (inside) cpuVisible[v * n + cpuGroupBase[group] + cpuCounts_[v * groups + group]++] = uint32_t(i);
      }
    }
    int64_t seen = 0;
    std::vector<int64_t> byLevel;
    for (size_t v = 0; v < cameraViews_; ++v)
      for (size_t k = 0; k < groups; ++k) {
        seen += cpuCounts_[v * groups + k];
        if (byLevel.size() <= groups_[k].level) byLevel.resize(groups_[k].level + 1, 0);
        byLevel[groups_[k].level] += cpuCounts_[v * groups + k];
      }
    *lastVisible_ = seen;
    *lastByLevel_ = std::move(byLevel);
    int64_t triangles = 0;
    for (const Part& p : parts_)
      for (size_t v = 0; v < cameraViews_; ++v) triangles += int64_t(cpuCounts_[v * groups + p.group]) * (p.indexCount / 3);
    *lastTriangles_ = triangles;
    if (reportKept_) {
      std::vector<std::vector<KeptInstance>> kept(cameraViews_);
      for (size_t v = 0; v < cameraViews_; ++v)
        for (size_t k = 0; k < groups; ++k)
          for (uint32_t j = 0; j < cpuCounts_[v * groups + k]; ++j)
            kept[v].push_back({set_.instances[cpuVisible[v * n + cpuGroupBase[k] + j]].id, groups_[k].level});
      *lastKept_ = std::move(kept);
    }
  }

  struct Upload {
    BufferRef instances, cells, visible, groupBase;
  };
  const size_t visibleBytes = std::max<size_t>(cpuVisible.size(), 1) * 4;  // before the execute takes the list
  const Upload& up = graph.addPass<Upload>(
      name_ + "_upload",
      [&](PassBuilder& b, Upload& d) {
        d.instances = b.write(graph.persistentBuffer(bufferName_, BufferDesc{n * sizeof(GpuInstance)}),
                              Usage::Transfer);
        d.cells = b.create(name_ + "_cells", BufferDesc{cells.size() * sizeof(glm::vec4)}, Usage::Transfer);
        if (!gpu) {
          d.visible = b.create(name_ + "_visible", BufferDesc{visibleBytes}, Usage::Transfer);
          d.groupBase = b.create(name_ + "_group_base", BufferDesc{groups * 4}, Usage::Transfer);
        }
      },
      [this, cells, cpuVisible = std::move(cpuVisible), cpuGroupBase](const Upload& d, const PassResources& r) {
        if (r.fresh(d.instances) || uploaded_ != revision_) {
          upload(r.buffer(d.instances), set_.instances);
          uploaded_ = revision_;
          *lastUploadBytes_ = set_.instances.size() * sizeof(GpuInstance);
        } else {
          size_t bytes = 0;
          for (const auto& [first, count] : pending_) {
            glNamedBufferSubData(r.buffer(d.instances), GLintptr(first * sizeof(GpuInstance)),
                                 GLsizeiptr(count * sizeof(GpuInstance)), set_.instances.data() + first);
            bytes += count * sizeof(GpuInstance);
          }
          *lastUploadBytes_ = bytes;
        }
        pending_.clear();
        upload(r.buffer(d.cells), cells);
        if (d.visible.valid()) upload(r.buffer(d.visible), cpuVisible);
        if (d.groupBase.valid()) upload(r.buffer(d.groupBase), cpuGroupBase);
      });
  instanceBuffer_ = up.instances;
  cells_ = up.cells;
  visible_ = up.visible;
  groupBase_ = up.groupBase;
  commands_ = {};
  if (!gpu) return;

  // The GPU's choices, lists and commands (one per view and part):
  //   instance_lod.comp     per instance: its level, or culled by distance;
  //                         each group's total
  //   instance_groups.comp  each group's first slot in a view's list
  //   instance_cull.comp    per instance and view: the sphere test, a slot
  //                         in the view's part of its group
  //   instance_commands.comp per view and part: the instance count.
  std::vector<glm::uvec4> parts;
  for (const Part& p : parts_) parts.emplace_back(p.indexCount, p.firstIndex, p.group, 0u);
  struct Cull {
    BufferRef instances, cells, visible, counts, commands, typeCull, planes, groupBase, parts, levels, totals, lodDistances;
  };
  const Cull& cull = graph.addPass<Cull>(
      name_ + "_cull",
      [&](PassBuilder& b, Cull& d) {
        d.instances = b.read(up.instances);
        d.cells = b.read(up.cells);
        d.visible = b.create(name_ + "_visible", BufferDesc{views * n * 4});
        d.counts = b.create(name_ + "_counts", BufferDesc{views * groups * 4});
        d.commands = b.create(name_ + "_commands", BufferDesc{views * parts.size() * kCommandBytes});
        d.groupBase = b.create(name_ + "_group_base", BufferDesc{groups * 4});
        d.levels = b.create(name_ + "_levels", BufferDesc{n * 4});
        d.totals = b.create(name_ + "_group_totals", BufferDesc{groups * 4});
        d.typeCull = b.create(name_ + "_types", BufferDesc{typeCull.size() * sizeof(GpuTypeCull)}, Usage::Transfer);
        d.planes = b.create(name_ + "_planes", BufferDesc{std::max<size_t>(planes.size(), 1) * sizeof(glm::vec4)},
                            Usage::Transfer);
        d.lodDistances = b.create(name_ + "_lod_distances", BufferDesc{groups * 4}, Usage::Transfer);
        d.parts = b.create(name_ + "_parts", BufferDesc{parts.size() * sizeof(glm::uvec4)}, Usage::Transfer);
      },
      [this, &frame, n, views, types, groups, cellCount = cells.size(), typeCull, planes, parts, lodDistances](
          const Cull& d, const PassResources& r) {
        upload(r.buffer(d.typeCull), typeCull);
        upload(r.buffer(d.planes), planes);
        upload(r.buffer(d.lodDistances), lodDistances);
        upload(r.buffer(d.parts), parts);
        const GLuint zero = 0;
        glClearNamedBufferData(r.buffer(d.counts), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        glClearNamedBufferData(r.buffer(d.totals), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInstanceBinding, r.buffer(d.instances));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCellBinding, r.buffer(d.cells));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVisibleBinding, r.buffer(d.visible));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTypeCullBinding, r.buffer(d.typeCull));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPlanesBinding, r.buffer(d.planes));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCountsBinding, r.buffer(d.counts));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kGroupBaseBinding, r.buffer(d.groupBase));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLevelsBinding, r.buffer(d.levels));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kGroupTotalsBinding, r.buffer(d.totals));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLodDistanceBinding, r.buffer(d.lodDistances));
        // Uploads and clears before the dispatches read them.
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        const GLuint instanceGroups = GLuint((n + 63) / 64);
        GlProgram& lod = frame.res.program({"", "", "instance_lod.comp", {}});
        lod.use();
        lod.set("uInstances", unsigned(n));
        lod.set("uTypes", unsigned(types));
        lod.set("uCells", unsigned(cellCount));
        lod.set("uLodEye", lodEye_);
        lod.set("uCullSlack", kCullSlack);
        glDispatchCompute(instanceGroups, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the totals
        GlProgram& prefix = frame.res.program({"", "", "instance_groups.comp", {}});
        prefix.use();
        prefix.set("uGroups", unsigned(groups));
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the levels and the groups' places
        GlProgram& cullProgram = frame.res.program({"", "", "instance_cull.comp", {}});
        cullProgram.use();
        cullProgram.set("uInstances", unsigned(n));
        cullProgram.set("uViews", unsigned(views));
        cullProgram.set("uCameraViews", unsigned(cameraViews_));
        cullProgram.set("uGroups", unsigned(groups));
        glDispatchCompute(instanceGroups, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the counts
        GlProgram& commands = frame.res.program({"", "", "instance_commands.comp", {}});
        commands.use();
        commands.set("uParts", unsigned(parts.size()));
        commands.set("uViews", unsigned(views));
        commands.set("uGroups", unsigned(groups));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPartsBinding, r.buffer(d.parts));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCommandsBinding, r.buffer(d.commands));
        glDispatchCompute(GLuint((parts.size() * views + 63) / 64), 1, 1);
        // The passes that draw read the commands, lists and places: the
        // graph's barrier (Usage::Indirect and Storage reads of Storage writes).
      });
  visible_ = cull.visible;
  groupBase_ = cull.groupBase;
  commands_ = cull.commands;
  // The visible counts, a frame or more later, for the statistics.
  std::vector<uint32_t> groupLevel;
  for (const Group& g : groups_) groupLevel.push_back(g.level);
  std::vector<int64_t> groupTriangles(groups, 0);  // every part of a group's mesh
  for (const Part& p : parts_) groupTriangles[p.group] += p.indexCount / 3;
  graph.readback(name_ + "_counts", cull.counts, 0, views * groups * 4,
                 [seen = lastVisible_, byLevel = lastByLevel_, drawn = lastTriangles_, cameraViews = cameraViews_,
                  groupLevel, groupTriangles](const void* data, size_t) {
                   const auto* c = static_cast<const uint32_t*>(data);
                   const size_t groupCount = groupLevel.size();
                   int64_t sum = 0, triangles = 0;
                   std::vector<int64_t> levels;
                   for (size_t v = 0; v < cameraViews; ++v)
                     for (size_t k = 0; k < groupCount; ++k) {
                       sum += c[v * groupCount + k];
                       triangles += int64_t(c[v * groupCount + k]) * groupTriangles[k];
                       if (levels.size() <= groupLevel[k]) levels.resize(groupLevel[k] + 1, 0);
                       levels[groupLevel[k]] += c[v * groupCount + k];
                     }
                   *seen = sum;
                   *byLevel = std::move(levels);
                   *drawn = triangles;
                 });
  if (reportKept_ && cameraViews_ > 0) {
    // Three copies of one frame: the counts and the groups' places land in
    // `pending`, the lists' copy (queued last, so delivered last: the pool
    // delivers in order behind fences that signal in order) reads them.
    struct Pending {
      std::vector<uint32_t> counts, base;
    };
    auto pending = std::make_shared<Pending>();
    auto copyInto = [pending](std::vector<uint32_t> Pending::*member) {
      return [pending, member](const void* data, size_t bytes) {
        const auto* p = static_cast<const uint32_t*>(data);
        ((*pending).*member).assign(p, p + bytes / 4);
      };
    };
    graph.readback(name_ + "_kept_counts", cull.counts, 0, views * groups * 4, copyInto(&Pending::counts));
    graph.readback(name_ + "_kept_base", cull.groupBase, 0, groups * 4, copyInto(&Pending::base));
    std::vector<uint32_t> ids(n);
    for (size_t i = 0; i < n; ++i) ids[i] = set_.instances[i].id;
    graph.readback(name_ + "_kept", cull.visible, 0, cameraViews_ * n * 4,
                   [pending, ids = std::move(ids), groupLevel, kept = lastKept_, cameraViews = cameraViews_, n](
                       const void* data, size_t bytes) {
                     const size_t groupCount = groupLevel.size();
                     if (bytes < cameraViews * n * 4 || pending->counts.size() < cameraViews * groupCount ||
                         pending->base.size() < groupCount)
                       return;  // a copy failed: keep the last report
                     const auto* list = static_cast<const uint32_t*>(data);
                     std::vector<std::vector<KeptInstance>> out(cameraViews);
                     for (size_t v = 0; v < cameraViews; ++v)
                       for (size_t k = 0; k < groupCount; ++k)
                         for (uint32_t j = 0; j < pending->counts[v * groupCount + k]; ++j) {
                           const uint32_t i = list[v * n + pending->base[k] + j];
                           out[v].push_back({i < n ? ids[i] : 0xFFFFFFFFu, groupLevel[k]});
                         }
                     *kept = std::move(out);
                   });
  }
}

void InstancedSource::declare(PassBuilder& b, DrawVariant) const {
  if (!active_) return;
  b.read(instanceBuffer_);
  b.read(cells_);
  b.read(visible_);
  b.read(groupBase_);
  if (commands_.valid()) b.read(commands_, Usage::Indirect);
}

void InstancedSource::bindInstances(const PassResources& r) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInstanceBinding, r.buffer(instanceBuffer_));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCellBinding, r.buffer(cells_));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVisibleBinding, r.buffer(visible_));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kGroupBaseBinding, r.buffer(groupBase_));
  if (commands_.valid()) glBindBuffer(GL_DRAW_INDIRECT_BUFFER, r.buffer(commands_));
}

size_t InstancedSource::triangles(SurfaceSet surfaces) const {
  if (culling_ == Culling::Gpu || !active_) return 0;  // the GPU's counts come back later (lastVisible)
  size_t n = 0;
  const size_t groups = groups_.size();
  for (const Part& p : parts_)
    if (wanted(p, surfaces))
      for (size_t v = 0; v < cameraViews_; ++v) n += size_t(cpuCounts_[v * groups + p.group]) * (p.indexCount / 3);
  return n;
}

// Draws view `view`'s visible instances of every wanted part: one program
// per material variant (or the pass's fragment), mesh.vert's INSTANCED.
void InstancedSource::drawParts(FrameContext& frame, const PassResources& r, size_t view, const DrawCall& call) {
  const size_t n = set_.instances.size();
  bindInstances(r);
  std::vector<std::string> defines = call.defines;
  defines.push_back("INSTANCED");
  MaterialBinding binding(frame, defines, call.fragment);
  // Picking draws one pixel into a 1x1 target: the dither (shaders/
  // instance_fade.glsl) takes that pixel's place in the view.
  const glm::ivec2 ditherOffset = call.variant == DrawVariant::Pick ? call.pickPixel : glm::ivec2(0);
  for (size_t k = 0; k < parts_.size(); ++k) {
    const Part& part = parts_[k];
    const InstanceType& type = set_.types[part.type];
    if (call.variant == DrawVariant::Surface && !wanted(part, call.surfaces)) continue;
    if (call.variant == DrawVariant::Depth && !type.castShadows) continue;
    const Group& group = groups_[part.group];
    if (!group.mesh) continue;  // an impostor: drawImpostors
    const DrawMaterial& mat = materials_->forDraw(group.materialDraw, part.submesh);
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
    p->set("uInstanceBase", unsigned(view * n));
    p->set("uGroup", part.group);
    p->set("uLodEye", lodEye_);
    // The wind's height: level 0's, so a level change does not change the sway.
    p->set("uInstanceType", glm::vec4(type.cullDistance, type.fadeLength, type.windResponse,
                                      type.windResponse > 0.0f ? types_[part.type].height : 0.0f));
    p->set("uDitherOffset", ditherOffset);
    const GLuint vao = group.mesh->vao;
    glBindVertexArray(vao);
    // Attribute 7 is the document meshes' object index (divisor 1): off,
    // so no instance reads past its buffer.
    glDisableVertexArrayAttrib(vao, 7);
    drawPart(frame, view, k, call, part.firstIndex);
    glEnableVertexArrayAttrib(vao, 7);
  }
  binding.finish();
  drawImpostors(frame, view, call, ditherOffset);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

// Part `k` of view `view` with the bound program and vertex array: by its
// indirect command (GPU culling) or with the CPU's count for its group.
void InstancedSource::drawPart(FrameContext& frame, size_t view, size_t k, const DrawCall& call, uint32_t firstIndex) {
  const Part& part = parts_[k];
  if (commands_.valid()) {
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                                reinterpret_cast<const void*>((view * parts_.size() + k) * kCommandBytes), 1, 0);
    ++frame.stats.drawCalls;
  } else if (const uint32_t count = cpuCounts_[view * groups_.size() + part.group]) {
    glDrawElementsInstanced(GL_TRIANGLES, GLsizei(part.indexCount), GL_UNSIGNED_INT,
                            reinterpret_cast<const void*>(uintptr_t(firstIndex) * sizeof(uint32_t)), GLsizei(count));
    ++frame.stats.drawCalls;
    if (call.variant == DrawVariant::Surface && call.surfaces == SurfaceSet::Opaque) {
      frame.stats.trianglesDrawn += size_t(count) * (part.indexCount / 3);
      frame.stats.instancesDrawn += count;
    }
  }
}

// View `view`'s impostors: one card per instance (shaders/impostor.vert),
// lit, picked or cast by shaders/impostor.frag's variant for the call.
void InstancedSource::drawImpostors(FrameContext& frame, size_t view, const DrawCall& call, glm::ivec2 ditherOffset) {
  // Impostors are cut out, opaque: none in the transparency passes. The
  // capture of every surface (the layered depth of field's A-buffer,
  // SurfaceSet::All) takes them with impostor.frag's own variants of the
  // A-buffer's count and key shaders, and its lit HS_OIT one.
  const bool capture = call.variant == DrawVariant::Surface && call.surfaces == SurfaceSet::All;
  if (call.variant == DrawVariant::Surface && call.surfaces == SurfaceSet::Translucent) return;
  const char* captureVariant = nullptr;
  if (capture && call.fragment == "abuffer_count.frag") captureVariant = "IMPOSTOR_ABUFFER_COUNT";
  else if (capture && call.fragment == "abuffer_keys.frag") captureVariant = "IMPOSTOR_ABUFFER_KEYS";
  else if (call.variant == DrawVariant::Surface && !call.fragment.empty()) return;  // a pass's shader for meshes only
  const size_t n = set_.instances.size();
  std::vector<std::string> defines = {"IMPOSTOR_FRAMES " + std::to_string(kImpostorFrames),
                                      "IMPOSTOR_FRAME_PIXELS " + std::to_string(kImpostorFramePixels)};
  if (call.variant == DrawVariant::Pick) defines.push_back("IMPOSTOR_PICK");
  else if (call.variant == DrawVariant::Depth) defines.push_back("IMPOSTOR_DEPTH");
  else if (captureVariant) defines.push_back(captureVariant);
  else defines.insert(defines.end(), call.defines.begin(), call.defines.end());
  bool bound = false;
  for (size_t k = 0; k < parts_.size(); ++k) {
    const Part& part = parts_[k];
    const Group& group = groups_[part.group];
    const TypeFrame& tf = types_[part.type];
    const InstanceType& type = set_.types[part.type];
    if (group.mesh || !tf.impostor) continue;
    if (call.variant == DrawVariant::Depth && !type.castShadows) continue;
    GlProgram& p = frame.res.program({"impostor.vert", "impostor.frag", "", defines});
    if (!bound) {
      p.use();
      glBindVertexArray(frame.res.impostors.cardVao());
      bound = true;
    }
    p.set("uInstanceBase", unsigned(view * n));
    p.set("uGroup", part.group);
    p.set("uLodEye", lodEye_);
    p.set("uInstanceType", glm::vec4(type.cullDistance, type.fadeLength, 0.0f, 0.0f));
    p.set("uDitherOffset", ditherOffset);
    p.set("uImpostorSphere", tf.impostor->sphere);
    p.set("uImpostorFacing", call.variant == DrawVariant::Depth ? 1 : 0);
    p.set("uMaterial", unsigned(materials_->forDraw(group.materialDraw, tf.impostorSubmesh).index));
    if (call.variant == DrawVariant::Pick) p.set("uPickBase", call.pickBase);
    glBindTextureUnit(3, tf.impostor->albedo.id());
    glBindTextureUnit(4, tf.impostor->normalDepth.id());
    drawPart(frame, view, k, call, 0);
  }
  if (bound) {
    glBindTextureUnit(3, 0);
    glBindTextureUnit(4, 0);
    glBindVertexArray(0);
  }
}

void InstancedSource::draw(FrameContext& frame, const DrawCall& call, const PassResources& r) {
  if (!active_) return;
  const size_t view = call.variant == DrawVariant::Depth ? cameraViews_ + call.shadowView : call.view;
  // The pick frame draws view 0 (its one view); shadow views follow the camera views.
  drawParts(frame, r, view, call);
}

}  // namespace hs::render
