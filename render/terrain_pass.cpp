#include "render/terrain_pass.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <limits>
#include <set>

namespace hs::render {
namespace {

constexpr int kQuadrantQuads = kTerrainGridQuads / 2;
enum Unit { kUnitHeight = 0, kUnitHoles = 1, kUnitWeights = 2, kUnitAlbedo = 3, kUnitNormal = 4 };

}  // namespace

bool TerrainPass::initialize(gl::ShaderLibrary& shaders, std::string& error) {
  if (ready_) return true;
  shade_ = shaders.get({"terrain.vert", "terrain.frag", "", {}}, error);
  pick_ = shade_ ? shaders.get({"terrain.vert", "terrain_pick.frag", "", {}}, error) : nullptr;
  if (!shade_ || !pick_) return false;
  shaders_ = &shaders;
  // The quadrant grid: (Q+1)^2 vertices on integer grid positions; two
  // triangles per quad split (i,j)-(i+1,j+1), as the full-resolution mesh,
  // so level 0 is that mesh exactly and morphed quads fold into the next
  // level's triangles.
  std::vector<glm::i16vec2> verts;
  for (int j = 0; j <= kQuadrantQuads; ++j)
    for (int i = 0; i <= kQuadrantQuads; ++i) verts.emplace_back(int16_t(i), int16_t(j));
  std::vector<uint16_t> idx;
  const int row = kQuadrantQuads + 1;
  for (int j = 0; j < kQuadrantQuads; ++j)
    for (int i = 0; i < kQuadrantQuads; ++i) {
      const uint16_t a = uint16_t(j * row + i), b = uint16_t(a + 1), c = uint16_t(a + row + 1), d = uint16_t(a + row);
      idx.insert(idx.end(), {a, b, c, a, c, d});
    }
  gridIndices_ = GLsizei(idx.size());
  glCreateBuffers(1, &gridVbo_);
  glNamedBufferStorage(gridVbo_, GLsizeiptr(verts.size() * sizeof(glm::i16vec2)), verts.data(), 0);
  glCreateBuffers(1, &gridIbo_);
  glNamedBufferStorage(gridIbo_, GLsizeiptr(idx.size() * sizeof(uint16_t)), idx.data(), 0);
  glCreateVertexArrays(1, &vao_);
  glVertexArrayVertexBuffer(vao_, 0, gridVbo_, 0, sizeof(glm::i16vec2));
  glVertexArrayAttribIFormat(vao_, 0, 2, GL_SHORT, 0);
  glVertexArrayAttribBinding(vao_, 0, 0);
  glEnableVertexArrayAttrib(vao_, 0);
  glVertexArrayAttribIFormat(vao_, 1, 4, GL_INT, 0);
  glVertexArrayAttribBinding(vao_, 1, 1);
  glVertexArrayBindingDivisor(vao_, 1, 1);
  glEnableVertexArrayAttrib(vao_, 1);
  glVertexArrayElementBuffer(vao_, gridIbo_);
  for (GlProgram* p : {shade_, pick_}) {
    p->set("uHeight", kUnitHeight);
    p->set("uHoles", kUnitHoles);
  }
  shade_->set("uWeights", kUnitWeights);
  shade_->set("uAlbedoTex", kUnitAlbedo);
  shade_->set("uNormalTex", kUnitNormal);
  ready_ = true;
  return true;
}

GlProgram* TerrainPass::shadingProgram(const std::vector<std::string>& defines) {
  if (defines.empty()) return shade_;
  std::string error;
  GlProgram* p = shaders_->get({"terrain.vert", "terrain.frag", "", defines}, error);
  if (!p) {
    // The variant compiles from the same sources as shade_, which did.
    std::fprintf(stderr, "hybridscape: internal error: %s\n", error.c_str());
    return nullptr;
  }
  p->set("uHeight", kUnitHeight);
  p->set("uHoles", kUnitHoles);
  p->set("uWeights", kUnitWeights);
  p->set("uAlbedoTex", kUnitAlbedo);
  p->set("uNormalTex", kUnitNormal);
  return p;
}

void TerrainPass::release() {
  if (!ready_) return;
  cache_.clear();
  for (auto& [id, m] : materials_) m.release();
  materials_.clear();
  glDeleteVertexArrays(1, &vao_);
  GLuint buffers[3] = {gridVbo_, gridIbo_, instanceVbo_};
  glDeleteBuffers(3, buffers);
  vao_ = gridVbo_ = gridIbo_ = instanceVbo_ = 0;
  instanceCapacity_ = 0;
  shade_ = pick_ = nullptr;  // the library owns them
  ready_ = false;
}

std::vector<scene::EntityId> TerrainPass::visibleTerrains(const scene::SceneState& state) {
  if (state.terrains.empty()) return {};
  return scene::terrainEntities(state, true);
}

void TerrainPass::collect(const scene::SceneState& state) {
  cache_.collect(state);
  std::set<uint64_t> live;
  for (const auto& [id, t] : state.terrains)
    if (t.data) live.insert(t.data->instance());
  for (auto it = materials_.begin(); it != materials_.end();) {
    if (live.count(it->first)) {
      ++it;
    } else {
      it->second.release();
      it = materials_.erase(it);
    }
  }
}

bool TerrainPass::prepare(const scene::SceneState& state, scene::EntityId entity, const RenderView& view,
                          Prepared& out, TerrainFrameStats* stats, const Frustum* cull) {
  const scene::TerrainAsset* asset = scene::terrainOf(state, entity);
  if (!asset) return false;
  out.asset = asset;
  out.gpu = cache_.get(*asset->data, stats ? &stats->upload : nullptr);
  const terrain::Heightfield& hf = asset->data->heights();
  // In double until the numbers are small (DESIGN.md).
  const glm::dvec3 origin = scene::terrainWorldOrigin(state, entity);
  const glm::dvec3 camLocal = view.eye - origin;
  const glm::dvec2 sp = hf.spacing();
  const double limit = double(1 << 30);
  const glm::dvec2 whole = glm::clamp(glm::floor(glm::dvec2(camLocal) / sp), glm::dvec2(-limit), glm::dvec2(limit));
  out.cameraSample = glm::ivec2(whole);
  out.cameraRest = glm::vec3(glm::dvec3(glm::dvec2(camLocal) - whole * sp, camLocal.z));
  out.lodEye = view.eye;

  const auto t0 = std::chrono::steady_clock::now();
  const Frustum frustum = frustumOf(view);
  LodInput in;
  in.tree = &out.gpu->tree();
  in.error = &out.gpu->lodError();
  in.spacing = sp;
  in.samplesX = hf.samplesX();
  in.samplesY = hf.samplesY();
  in.cameraLocal = camLocal;
  in.originRelative = origin - view.eye;
  in.frustum = cull ? cull : &frustum;
  in.pixelsPerUnit = lodPixelsPerUnit(view);
  in.errorPixels = state.find(entity)->terrain->lodErrorPixels;
  out.lod = selectLod(in);
  if (stats) {
    stats->selectMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    stats->nodesCulled += out.lod.nodesCulled;
  }
  return true;
}

void TerrainPass::bindCommon(GlProgram& p, const Prepared& t, const RenderView& view) {
  const terrain::Heightfield& hf = t.asset->data->heights();
  p.use();
  glProgramUniform2i(p.id(), p.loc("uSamples"), hf.samplesX(), hf.samplesY());
  p.set("uSpacing", glm::vec2(hf.spacing()));
  glProgramUniform2i(p.id(), p.loc("uCameraSample"), t.cameraSample.x, t.cameraSample.y);
  p.set("uCameraRest", t.cameraRest);
  std::array<glm::vec2, kTerrainMaxLevels> morph{};
  for (int l = 0; l < kTerrainMaxLevels; ++l) {
    const double start = t.lod.morphStart[size_t(l)], end = t.lod.range[size_t(l)];
    // The morph completes at 98% of the range, not at its very end: a
    // vertex on a boundary with the next level (d >= range) must reach k = 1
    // exactly, and (d - start) / (end - start) in float can stop a rounding
    // short of it, leaving a pinhole at the T-junction.
    morph[size_t(l)] = std::isfinite(start) && end > start
                           ? glm::vec2(float(start), float(1.0 / (0.98 * (end - start))))
                           : glm::vec2(3.0e38f, 0.0f);
  }
  glProgramUniform2fv(p.id(), p.loc("uMorph"), kTerrainMaxLevels, &morph[0].x);
  p.set("uEyeFromLod", glm::vec3(view.eye - t.lodEye));
  p.set("uHasHoles", t.gpu->holesTexture() != 0);
  glBindTextureUnit(kUnitHeight, t.gpu->heightTexture());
  glBindTextureUnit(kUnitHoles, t.gpu->holesTexture());
}

size_t TerrainPass::drawInstances(const Prepared& t) {
  const auto& patches = t.lod.patches;
  if (patches.empty()) return 0;
  std::vector<glm::ivec4> inst;
  inst.reserve(patches.size());
  for (const LodPatch& p : patches) inst.emplace_back(p.x0, p.y0, p.scale, p.level);
  const size_t bytes = inst.size() * sizeof(glm::ivec4);
  if (bytes > instanceCapacity_) {
    if (instanceVbo_) glDeleteBuffers(1, &instanceVbo_);
    instanceCapacity_ = std::max<size_t>(bytes * 2, 64 * 1024);
    glCreateBuffers(1, &instanceVbo_);
    glNamedBufferStorage(instanceVbo_, GLsizeiptr(instanceCapacity_), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glVertexArrayVertexBuffer(vao_, 1, instanceVbo_, 0, sizeof(glm::ivec4));
  }
  glNamedBufferSubData(instanceVbo_, 0, GLsizeiptr(bytes), inst.data());
  glBindVertexArray(vao_);
  glDrawElementsInstanced(GL_TRIANGLES, gridIndices_, GL_UNSIGNED_SHORT, nullptr, GLsizei(inst.size()));
  return t.lod.triangles();
}

TerrainFrameStats TerrainPass::draw(const scene::SceneState& state, const std::vector<scene::EntityId>& entities,
                                    const RenderView& view, const RenderView& lodView,
                                    const std::vector<std::string>& defines) {
  TerrainFrameStats stats;
  if (!ready_) return stats;
  collect(state);
  GlProgram* variant = shadingProgram(defines);
  if (!variant) return stats;
  GlProgram& p = *variant;
  p.use();
  for (scene::EntityId id : entities) {
    Prepared t;
    if (!prepare(state, id, lodView, t, &stats)) continue;
    bindCommon(p, t, view);
    // Materials: the document's values; weights from the GPU copy.
    const auto& mats = t.asset->materials;
    const int layers = std::min({int(mats.size()), t.asset->data->terrain().paint.layerCount(), 16});
    TerrainMaterialTextures& tex = materials_[t.asset->data->instance()];
    for (const std::string& problem : tex.update(mats))
      newProblems_.push_back("terrain '" + t.asset->name + "', " + problem);
    // Only the layers that weigh anything somewhere: a layer never painted
    // is a constant 0 (gpu_terrain.h) and would cost every pixel a turn of
    // the shader's loop for nothing (three of the demo's eight).
    int slice[16], albedoLayer[16], normalLayer[16];
    float weightConst[16], rough[16], tiling[16];
    glm::vec3 albedo[16];
    int drawn = 0;
    for (int i = 0; i < layers; ++i) {
      if (t.gpu->weightSlice(i) < 0 && t.gpu->constWeight(i) == 0.0f) continue;
      slice[drawn] = t.gpu->weightSlice(i);
      weightConst[drawn] = t.gpu->constWeight(i);
      albedo[drawn] = mats[size_t(i)].albedo;
      rough[drawn] = mats[size_t(i)].roughness;
      tiling[drawn] = std::max(mats[size_t(i)].tilingMetres, 1e-3f);
      albedoLayer[drawn] = tex.albedoSlice(i);
      normalLayer[drawn] = tex.normalSlice(i);
      ++drawn;
    }
    p.set("uLayerCount", drawn);
    p.set("uWeightGroups", t.gpu->weightGroups());
    if (drawn > 0) {
      glProgramUniform1iv(p.id(), p.loc("uWeightSlice"), drawn, slice);
      glProgramUniform1fv(p.id(), p.loc("uWeightConst"), drawn, weightConst);
      glProgramUniform3fv(p.id(), p.loc("uAlbedo"), drawn, &albedo[0].x);
      glProgramUniform1fv(p.id(), p.loc("uRoughness"), drawn, rough);
      glProgramUniform1fv(p.id(), p.loc("uTiling"), drawn, tiling);
      glProgramUniform1iv(p.id(), p.loc("uAlbedoLayer"), drawn, albedoLayer);
      glProgramUniform1iv(p.id(), p.loc("uNormalLayer"), drawn, normalLayer);
    }
    glBindTextureUnit(kUnitWeights, t.gpu->weightTexture());
    glBindTextureUnit(kUnitAlbedo, tex.albedo());
    glBindTextureUnit(kUnitNormal, tex.normal());
    stats.triangles += drawInstances(t);
    stats.patches += t.lod.patches.size();
    ++stats.terrains;
  }
  for (int u = kUnitHeight; u <= kUnitNormal; ++u) glBindTextureUnit(GLuint(u), 0);
  return stats;
}

void TerrainPass::drawPick(const scene::SceneState& state, const std::vector<scene::EntityId>& entities,
                           const RenderView& lodView, unsigned firstId) {
  if (!ready_) return;
  GlProgram& p = *pick_;
  p.use();
  for (size_t i = 0; i < entities.size(); ++i) {
    Prepared t;
    if (!prepare(state, entities[i], lodView, t, nullptr)) continue;
    bindCommon(p, t, lodView);
    p.set("uPickId", unsigned(firstId + i));
    drawInstances(t);
  }
  glBindTextureUnit(kUnitHeight, 0);
  glBindTextureUnit(kUnitHoles, 0);
}

size_t TerrainPass::drawShadow(const scene::SceneState& state, const std::vector<scene::EntityId>& entities,
                               const RenderView& lodView, const Frustum& volume) {
  if (!ready_) return 0;
  // The id program: its fragment shader drops holes like terrain.frag; with
  // no colour attachment its id goes nowhere.
  GlProgram& p = *pick_;
  p.use();
  size_t triangles = 0;
  for (scene::EntityId id : entities) {
    Prepared t;
    if (!prepare(state, id, lodView, t, nullptr, &volume)) continue;
    bindCommon(p, t, lodView);
    triangles += drawInstances(t);
  }
  glBindTextureUnit(kUnitHeight, 0);
  glBindTextureUnit(kUnitHoles, 0);
  return triangles;
}

TerrainUploadStats TerrainPass::sync(const scene::TerrainData& data) {
  TerrainUploadStats s;
  if (ready_) cache_.get(data, &s);
  return s;
}

LodSelection TerrainPass::select(const scene::SceneState& state, scene::EntityId entity, const RenderView& view) {
  Prepared t;
  if (!ready_ || !prepare(state, entity, view, t, nullptr)) return {};
  return t.lod;
}

size_t TerrainPass::gpuBytes() const {
  size_t b = cache_.gpuBytes();
  for (const auto& [id, m] : materials_) b += m.gpuBytes();
  return b;
}

std::vector<std::string> TerrainPass::takeMaterialProblems() {
  std::vector<std::string> out;
  out.swap(newProblems_);
  return out;
}

}  // namespace hs::render
