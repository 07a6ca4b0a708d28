#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <unordered_map>

#include <epoxy/gl.h>
#include <glm/gtc/matrix_inverse.hpp>

#include "render/frame_targets.h"
#include "render/gl_program.h"
#include "render/gpu_mesh_cache.h"
#include "render/mesh_lod.h"
#include "render/terrain_pass.h"

namespace hs::render {
namespace {

constexpr int kMaxPointLights = 8;

// A visible mesh instance after culling, camera-relative.
struct DrawItem {
  scene::EntityId id;
  const GpuMesh* mesh;
  glm::mat4 modelView;
  glm::mat3 normalMatrix;
  glm::vec3 tint;
};

glm::mat4 toFloat(const glm::dmat4& m) { return glm::mat4(m); }

}  // namespace

struct Renderer::Impl {
  bool ready = false;
  GlProgram meshProg, pickProg, skyProg, gridProg, overlayProg, tonemapProg, fxaaProg;
  GpuMeshCache cache;
  TerrainPass terrain;  // runs only for scenes with a visible terrain
  FrameTargets targets;
  GLuint emptyVao = 0;
  GLuint overlayVao = 0, overlayVbo = 0;
  size_t overlayCapacity = 0;
  // Timer queries in a ring so reading one never stalls on the current frame.
  GLuint timers[3] = {0, 0, 0};
  int timerFrame = 0;
  double lastGpuMs = -1.0;
  bool hdrKept = false;

  struct Lights {
    bool hasSun = false;
    glm::dvec3 sunDirWorld{0, 0, 1};  // towards the sun
    glm::vec3 sunColor{0.0f};
    int pointCount = 0;
    glm::vec3 pointPosView[kMaxPointLights];
    glm::vec3 pointColor[kMaxPointLights];
    float pointRange[kMaxPointLights];
  };

  // World matrices for every entity, parents first (one pass, no re-walking).
  static void worldMatrices(const scene::SceneState& s, std::unordered_map<scene::EntityId, glm::dmat4>& out) {
    out.reserve(s.entities.size());
    struct Item {
      scene::EntityId id;
      glm::dmat4 parent;
    };
    std::vector<Item> stack;
    for (auto it = s.roots.rbegin(); it != s.roots.rend(); ++it) stack.push_back({*it, glm::dmat4(1.0)});
    while (!stack.empty()) {
      const Item item = stack.back();
      stack.pop_back();
      const scene::Entity* e = s.find(item.id);
      if (!e || out.count(item.id)) continue;
      const glm::dmat4 w = item.parent * e->transform.matrix();
      out.emplace(item.id, w);
      for (auto c = e->children.rbegin(); c != e->children.rend(); ++c) stack.push_back({*c, w});
    }
  }

  Lights gatherLights(const scene::SceneState& s, const std::unordered_map<scene::EntityId, glm::dmat4>& world,
                      const RenderView& view) {
    Lights l;
    const glm::dmat3 viewRot = view.viewRotation();
    for (scene::EntityId id : s.depthFirstOrder()) {
      const scene::Entity& e = *s.find(id);
      if (!e.light || !s.effectivelyVisible(id)) continue;
      const glm::dmat4& w = world.at(id);
      const glm::vec3 color = e.light->color * e.light->intensity;
      if (e.light->type == scene::Light::Type::Sun) {
        if (l.hasSun) continue;  // one sun: the first in outliner order
        const glm::dvec3 travel = glm::normalize(glm::dmat3(w) * glm::dvec3(0, 0, -1));
        l.hasSun = true;
        l.sunDirWorld = -travel;
        l.sunColor = color;
      } else if (l.pointCount < kMaxPointLights) {
        const int i = l.pointCount++;
        l.pointPosView[i] = glm::vec3(viewRot * (glm::dvec3(w[3]) - view.eye));
        l.pointColor[i] = color;
        l.pointRange[i] = e.light->range;
      }
    }
    return l;
  }

  std::vector<DrawItem> collectDraws(const scene::SceneState& s,
                                     const std::unordered_map<scene::EntityId, glm::dmat4>& world,
                                     const RenderView& view, FrameStats& stats, const RenderView* lodView = nullptr) {
    const RenderView& lv = lodView ? *lodView : view;
    const glm::dvec3 lodEyeShift = view.eye - lv.eye;  // eye-relative to lodView-relative
    std::vector<DrawItem> items;
    const Frustum frustum = frustumOf(view);
    const glm::dmat4 viewRot4(view.viewRotation());
    for (const auto& [id, e] : s.entities) {
      if (!e.mesh || !s.effectivelyVisible(id)) continue;
      const scene::MeshAsset* asset = s.findAsset(e.mesh->mesh);
      if (!asset) continue;
      const GpuMesh* g = cache.get(*asset);
      if (!g) continue;
      const glm::dmat4& w = world.at(id);
      // Camera-relative model matrix, formed in double (DESIGN.md).
      glm::dmat4 rel = w;
      rel[3] = glm::dvec4(glm::dvec3(w[3]) - view.eye, 1.0);
      const glm::dvec3 centreRel = glm::dvec3(rel * glm::dvec4(glm::dvec3(g->bounds.center()), 1.0));
      const double maxScale = std::max({glm::length(glm::dvec3(w[0])), glm::length(glm::dvec3(w[1])),
                                        glm::length(glm::dvec3(w[2]))});
      if (!frustum.intersectsSphere(centreRel, double(g->bounds.radius()) * maxScale)) {
        ++stats.instancesCulled;
        continue;
      }
      // The coarsest LOD within the scene's pixel bound (mesh_lod.h).
      if (!asset->lods.empty()) {
        const MeshLodChoice lod = chooseMeshLod(asset->lodErrors(), centreRel + lodEyeShift, double(g->bounds.radius()),
                                                maxScale, lv, s.settings.meshLodErrorPixels);
        if (lod.level > 0) {
          if (const GpuMesh* coarser = cache.get(*asset, lod.level)) g = coarser;
          ++stats.instancesAtCoarserLod;
        }
      }
      const glm::dmat4 mv = viewRot4 * rel;
      items.push_back({id, g, toFloat(mv), glm::mat3(glm::inverseTranspose(glm::dmat3(mv))), e.mesh->tint});
    }
    return items;
  }

  void drawMeshes(const std::vector<DrawItem>& items, FrameStats& stats) {
    for (const DrawItem& it : items) {
      meshProg.set("uModelView", it.modelView);
      meshProg.set("uNormalMatrix", it.normalMatrix);
      glBindVertexArray(it.mesh->vao);
      const mesh::MeshData& m = *it.mesh->data;
      for (const mesh::Submesh& sm : m.submeshes) {
        glm::vec4 color(0.8f, 0.8f, 0.8f, 1.0f);
        GLuint tex = 0;
        if (sm.material >= 0 && size_t(sm.material) < m.materials.size()) {
          const mesh::Material& mat = m.materials[size_t(sm.material)];
          color = mat.baseColor;
          if (mat.diffuseTexture >= 0 && size_t(mat.diffuseTexture) < it.mesh->textures.size() && it.mesh->hasUvs)
            tex = it.mesh->textures[size_t(mat.diffuseTexture)];
        }
        meshProg.set("uBaseColor", color * glm::vec4(it.tint, 1.0f));
        meshProg.set("uHasTexture", tex != 0);
        if (tex) glBindTextureUnit(0, tex);
        glDrawElements(GL_TRIANGLES, GLsizei(sm.indexCount), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(uintptr_t(sm.firstIndex) * sizeof(uint32_t)));
        stats.trianglesDrawn += sm.indexCount / 3;
        ++stats.drawCalls;
      }
      ++stats.instancesDrawn;
    }
  }

  void drawOverlay(const Overlay& o, const RenderView& view, const glm::mat4& viewRot, const glm::mat4& proj) {
    struct V {
      glm::vec3 p;
      glm::vec4 c;
    };
    std::vector<V> verts;
    verts.reserve(o.lines.size() + o.triangles.size());
    for (const auto& v : o.lines) verts.push_back({glm::vec3(v.position - view.eye), v.color});
    for (const auto& v : o.triangles) verts.push_back({glm::vec3(v.position - view.eye), v.color});
    const size_t bytes = verts.size() * sizeof(V);
    if (bytes > overlayCapacity) {
      if (overlayVbo) glDeleteBuffers(1, &overlayVbo);
      glCreateBuffers(1, &overlayVbo);
      overlayCapacity = std::max<size_t>(bytes, 64 * 1024);
      glNamedBufferStorage(overlayVbo, GLsizeiptr(overlayCapacity), nullptr, GL_DYNAMIC_STORAGE_BIT);
      glVertexArrayVertexBuffer(overlayVao, 0, overlayVbo, 0, sizeof(V));
    }
    glNamedBufferSubData(overlayVbo, 0, GLsizeiptr(bytes), verts.data());
    overlayProg.use();
    overlayProg.set("uViewRot", viewRot);
    overlayProg.set("uProjection", proj);
    glBindVertexArray(overlayVao);
    if (o.onTop) glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    if (!o.triangles.empty()) glDrawArrays(GL_TRIANGLES, GLint(o.lines.size()), GLsizei(o.triangles.size()));
    if (!o.lines.empty()) glDrawArrays(GL_LINES, 0, GLsizei(o.lines.size()));
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
  }
};

Renderer::Renderer() : d_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

bool Renderer::initialized() const { return d_->ready; }

std::string currentGlDescription() {
  const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(r ? r : "?") + " | " + (v ? v : "?");
}

bool Renderer::initialize(std::string& error) {
  if (d_->ready) return true;
  if (epoxy_gl_version() < 45) {
    error = "OpenGL 4.5 is required, this context has " + currentGlDescription();
    return false;
  }
  struct P {
    GlProgram* prog;
    const char* vs;
    const char* fs;
  };
  for (const P& p : {P{&d_->meshProg, "mesh.vert", "mesh.frag"}, P{&d_->pickProg, "mesh.vert", "pick.frag"},
                     P{&d_->skyProg, "fullscreen.vert", "sky.frag"}, P{&d_->gridProg, "grid.vert", "grid.frag"},
                     P{&d_->overlayProg, "overlay.vert", "overlay.frag"},
                     P{&d_->tonemapProg, "fullscreen.vert", "tonemap.frag"},
                     P{&d_->fxaaProg, "fullscreen.vert", "fxaa.frag"}})
    if (!p.prog->build(p.vs, p.fs, error)) return false;
  if (!d_->terrain.initialize(error)) return false;
  glCreateVertexArrays(1, &d_->emptyVao);
  glCreateVertexArrays(1, &d_->overlayVao);
  glVertexArrayAttribFormat(d_->overlayVao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(d_->overlayVao, 0, 0);
  glEnableVertexArrayAttrib(d_->overlayVao, 0);
  glVertexArrayAttribFormat(d_->overlayVao, 1, 4, GL_FLOAT, GL_FALSE, sizeof(glm::vec3));
  glVertexArrayAttribBinding(d_->overlayVao, 1, 0);
  glEnableVertexArrayAttrib(d_->overlayVao, 1);
  glCreateQueries(GL_TIME_ELAPSED, 3, d_->timers);
  d_->meshProg.set("uAlbedo", 0);
  d_->tonemapProg.set("uScene", 0);
  d_->fxaaProg.set("uImage", 0);
  d_->ready = true;
  return true;
}

FrameStats Renderer::render(const scene::SceneState& state, const RenderView& view, unsigned targetFbo,
                            const RenderOptions& options) {
  FrameStats stats;
  if (!d_->ready || view.width <= 0 || view.height <= 0) return stats;
  const auto t0 = std::chrono::steady_clock::now();
  Impl& d = *d_;
  const scene::SceneSettings& settings = state.settings;
  const int samples = settings.antialiasing == scene::Antialiasing::Msaa4 ? 4 : 1;
  const bool fxaa = settings.antialiasing == scene::Antialiasing::Fxaa;
  d.targets.ensure(view.width, view.height, samples, fxaa);

  GLuint timer = 0;
  if (options.measureGpuTime) {
    // Read the query from two frames ago if it is done; never wait for it.
    const GLuint old = d.timers[(d.timerFrame + 1) % 3];
    GLint available = 0;
    if (d.timerFrame >= 2) glGetQueryObjectiv(old, GL_QUERY_RESULT_AVAILABLE, &available);
    if (available) {
      GLuint64 ns = 0;
      glGetQueryObjectui64v(old, GL_QUERY_RESULT, &ns);
      d.lastGpuMs = double(ns) * 1e-6;
    }
    timer = d.timers[d.timerFrame % 3];
    glBeginQuery(GL_TIME_ELAPSED, timer);
  }

  // Reversed-Z: depth 1 at the near plane, 0 at the far plane.
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glBindFramebuffer(GL_FRAMEBUFFER, d.targets.sceneFbo());
  glViewport(0, 0, view.width, view.height);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);  // scans are open surfaces, seen from both sides
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_GREATER);
  const float clearColor[4] = {0, 0, 0, 1};
  const float clearDepth = 0.0f;
  glClearBufferfv(GL_COLOR, 0, clearColor);
  glClearBufferfv(GL_DEPTH, 0, &clearDepth);

  std::unordered_map<scene::EntityId, glm::dmat4> world;
  Impl::worldMatrices(state, world);
  const Impl::Lights lights = d.gatherLights(state, world, view);
  const glm::dmat3 viewRotD = view.viewRotation();
  const glm::mat4 viewRot = glm::mat4(glm::dmat4(viewRotD));
  const glm::mat4 proj = toFloat(view.projection());

  // Opaque meshes.
  const std::vector<DrawItem> items = d.collectDraws(state, world, view, stats, options.lodView);
  if (!items.empty()) {
    GlProgram& p = d.meshProg;
    p.use();
    p.set("uProjection", proj);
    p.set("uHasSun", lights.hasSun);
    p.set("uSunDirView", glm::vec3(viewRotD * lights.sunDirWorld));
    p.set("uSunColor", lights.sunColor);
    p.set("uUpView", glm::vec3(viewRotD * glm::dvec3(0, 0, 1)));
    p.set("uSkyColor", settings.skyZenith);
    p.set("uGroundColor", settings.groundColor);
    p.set("uAmbient", settings.ambientIntensity);
    p.set("uShininess", 32.0f);
    p.set("uSpecular", 0.15f);
    p.set("uPointLightCount", lights.pointCount);
    if (lights.pointCount) {
      glProgramUniform3fv(p.id(), p.loc("uPointPosView"), lights.pointCount, &lights.pointPosView[0].x);
      glProgramUniform3fv(p.id(), p.loc("uPointColor"), lights.pointCount, &lights.pointColor[0].x);
      glProgramUniform1fv(p.id(), p.loc("uPointRange"), lights.pointCount, lights.pointRange);
    }
    d.drawMeshes(items, stats);
  }

  // Terrains, lit like the meshes (terrain_pass.h).
  if (const std::vector<scene::EntityId> terrains = TerrainPass::visibleTerrains(state); !terrains.empty()) {
    TerrainLighting tl;
    tl.hasSun = lights.hasSun;
    tl.sunDirView = glm::vec3(viewRotD * lights.sunDirWorld);
    tl.sunColor = lights.sunColor;
    tl.upView = glm::vec3(viewRotD * glm::dvec3(0, 0, 1));
    tl.sky = settings.skyZenith;
    tl.ground = settings.groundColor;
    tl.ambient = settings.ambientIntensity;
    tl.pointCount = lights.pointCount;
    tl.pointPosView = lights.pointPosView;
    tl.pointColor = lights.pointColor;
    tl.pointRange = lights.pointRange;
    const TerrainFrameStats ts = d.terrain.draw(state, terrains, view, tl);
    stats.trianglesDrawn += ts.triangles;
    stats.drawCalls += ts.terrains;
    stats.terrainTriangles = ts.triangles;
    stats.terrainPatches = ts.patches;
    stats.terrainUploadBytes = ts.upload.bytes;
    stats.terrainUploadMs = ts.upload.cpuMs;
  }

  // Sky where nothing was drawn (depth still at the cleared far value).
  {
    GlProgram& p = d.skyProg;
    p.use();
    p.set("uInvViewRot", glm::mat3(glm::transpose(viewRotD)));
    const double t = std::tan(view.fovY * 0.5);
    p.set("uTanHalfFov", glm::vec2(float(t * view.aspect()), float(t)));
    p.set("uSubpixel", glm::vec2(view.projectionShift));
    p.set("uZenith", settings.skyZenith);
    p.set("uHorizon", settings.skyHorizon);
    p.set("uGround", settings.groundColor);
    p.set("uHasSun", lights.hasSun);
    p.set("uSunDirWorld", glm::vec3(lights.sunDirWorld));
    p.set("uSunColor", lights.sunColor);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    glBindVertexArray(d.emptyVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthFunc(GL_GREATER);
  }

  // Ground grid, blended over what is there.
  if (settings.showGrid && options.showGrid) {
    GlProgram& p = d.gridProg;
    p.use();
    p.set("uViewRot", viewRot);
    p.set("uProjection", proj);
    const double extent = std::min(view.farClip, 20000.0);
    p.set("uExtent", float(extent));
    p.set("uCameraZ", float(view.eye.z));
    p.set("uCameraXY", glm::vec2(view.eye));
    // Camera position modulo the 100 m period of the two line spacings, in double.
    p.set("uOffset", glm::vec2(glm::mod(glm::dvec2(view.eye), glm::dvec2(100.0))));
    p.set("uFadeDistance", float(std::max(200.0, std::abs(view.eye.z) * 30.0)));
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glBindVertexArray(d.emptyVao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisable(GL_BLEND);
  }

  if (options.overlay && !options.overlay->empty()) d.drawOverlay(*options.overlay, view, viewRot, proj);

  // Resolve, tone map, anti-alias.
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  const GLuint hdrTexture = d.targets.resolve();
  d.hdrKept = options.keepHdr;
  glBindVertexArray(d.emptyVao);
  {
    GlProgram& p = d.tonemapProg;
    p.use();
    p.set("uExposure", settings.exposure);
    p.set("uFilmic", settings.tonemap == scene::Tonemap::Aces);
    p.set("uLumaInAlpha", fxaa);
    glBindFramebuffer(GL_FRAMEBUFFER, fxaa ? d.targets.ldrFbo() : targetFbo);
    glBindTextureUnit(0, hdrTexture);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  if (fxaa) {
    GlProgram& p = d.fxaaProg;
    p.use();
    p.set("uTexel", glm::vec2(1.0f / float(view.width), 1.0f / float(view.height)));
    glBindFramebuffer(GL_FRAMEBUFFER, targetFbo);
    glBindTextureUnit(0, d.targets.ldrTexture());
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }

  if (timer) {
    glEndQuery(GL_TIME_ELAPSED);
    ++d.timerFrame;
  }
  // Leave the state a host (Qt) expects.
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glDepthFunc(GL_LESS);
  glBindVertexArray(0);
  glUseProgram(0);
  glBindTextureUnit(0, 0);

  stats.gpuMs = d.lastGpuMs;
  stats.gpuBytes = d.cache.gpuBytes() + d.targets.gpuBytes() + d.terrain.gpuBytes();
  stats.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return stats;
}

void Renderer::clearTarget(unsigned fbo, float r, float g, float b) {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glClearColor(r, g, b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
}

Image Renderer::readDisplay(unsigned targetFbo, int width, int height) const {
  Image img;
  img.width = width;
  img.height = height;
  img.rgba8.resize(size_t(width) * size_t(height) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, targetFbo);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba8.data());
  flipRows(img.rgba8.data(), size_t(width) * 4, size_t(height));  // GL rows are bottom-up
  return img;
}

Image Renderer::readHdr() const {
  Image img;
  if (!d_->hdrKept) return img;
  img.width = d_->targets.width();
  img.height = d_->targets.height();
  img.rgbaF.resize(size_t(img.width) * size_t(img.height) * 4);
  glGetTextureImage(d_->targets.resolvedTexture(), 0, GL_RGBA, GL_FLOAT, GLsizei(img.rgbaF.size() * sizeof(float)),
                    img.rgbaF.data());
  flipRows(img.rgbaF.data(), size_t(img.width) * 4 * sizeof(float), size_t(img.height));  // GL rows are bottom-up
  return img;
}

void Renderer::readHdrInto(void* dst, size_t bytes) const {
  if (!d_->hdrKept) return;
  glGetTextureImage(d_->targets.resolvedTexture(), 0, GL_RGBA, GL_FLOAT, GLsizei(bytes), dst);
}

void Renderer::readDepth(void* dst) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, d_->targets.depthReadFbo());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, d_->targets.width(), d_->targets.height(), GL_DEPTH_COMPONENT, GL_FLOAT, dst);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

scene::EntityId Renderer::pick(const scene::SceneState& state, const RenderView& view, int x, int y) {
  if (!d_->ready || x < 0 || y < 0 || x >= view.width || y >= view.height) return scene::kNoEntity;
  Impl& d = *d_;
  d.targets.ensurePick();
  // Projection narrowed to the one pixel: the 1x1 target sees just it.
  const double cx = 2.0 * (x + 0.5) / view.width - 1.0;
  const double cy = 1.0 - 2.0 * (y + 0.5) / view.height;
  glm::dmat4 narrow(1.0);
  narrow[0][0] = view.width;
  narrow[1][1] = view.height;
  narrow[3][0] = -cx * view.width;
  narrow[3][1] = -cy * view.height;
  FrameStats unused;
  std::unordered_map<scene::EntityId, glm::dmat4> world;
  Impl::worldMatrices(state, world);
  const std::vector<DrawItem> items = d.collectDraws(state, world, view, unused);

  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glBindFramebuffer(GL_FRAMEBUFFER, d.targets.pickFbo());
  glViewport(0, 0, 1, 1);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_GREATER);
  const GLuint zero[4] = {0, 0, 0, 0};
  const float clearDepth = 0.0f;
  glClearBufferuiv(GL_COLOR, 0, zero);
  glClearBufferfv(GL_DEPTH, 0, &clearDepth);
  GlProgram& p = d.pickProg;
  p.use();
  p.set("uProjection", toFloat(narrow * view.projection()));
  for (size_t i = 0; i < items.size(); ++i) {
    p.set("uModelView", items[i].modelView);
    p.set("uPickId", unsigned(i + 1));
    glBindVertexArray(items[i].mesh->vao);
    for (const auto& sm : items[i].mesh->data->submeshes)
      glDrawElements(GL_TRIANGLES, GLsizei(sm.indexCount), GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(uintptr_t(sm.firstIndex) * sizeof(uint32_t)));
  }
  // Terrains after the meshes, ids following theirs (holes are not hit).
  const std::vector<scene::EntityId> terrains = TerrainPass::visibleTerrains(state);
  if (!terrains.empty()) d.terrain.drawPick(state, terrains, view, toFloat(narrow * view.projection()), unsigned(items.size() + 1));
  GLuint id = 0;
  glReadPixels(0, 0, 1, 1, GL_RED_INTEGER, GL_UNSIGNED_INT, &id);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glDepthFunc(GL_LESS);
  glBindVertexArray(0);
  glUseProgram(0);
  if (id > items.size() && id <= items.size() + terrains.size()) return terrains[id - items.size() - 1];
  return id > 0 && id <= items.size() ? items[id - 1].id : scene::kNoEntity;
}

void Renderer::collectGarbage(const scene::SceneState& state) { d_->cache.collect(state); }

TerrainUpload Renderer::syncTerrain(const scene::TerrainData& data, bool measureGpu) {
  GLuint query = 0;
  if (measureGpu) {
    glCreateQueries(GL_TIME_ELAPSED, 1, &query);
    glBeginQuery(GL_TIME_ELAPSED, query);
  }
  const TerrainUploadStats s = d_->terrain.sync(data);
  TerrainUpload out{s.bytes, s.regions, s.cpuMs, s.lodMs, s.full};
  if (measureGpu) {
    glEndQuery(GL_TIME_ELAPSED);
    const auto t0 = std::chrono::steady_clock::now();
    glFinish();
    out.finishMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
    out.gpuMs = double(ns) * 1e-6;
    glDeleteQueries(1, &query);
  }
  return out;
}

LodSelection Renderer::terrainLod(const scene::SceneState& state, scene::EntityId entity, const RenderView& view) {
  return d_->terrain.select(state, entity, view);
}

std::vector<std::string> Renderer::takeTerrainMaterialProblems() { return d_->terrain.takeMaterialProblems(); }

void Renderer::shutdown() {
  if (!d_->ready) return;
  d_->cache.clear();
  d_->terrain.release();
  d_->targets.release();
  glDeleteVertexArrays(1, &d_->emptyVao);
  glDeleteVertexArrays(1, &d_->overlayVao);
  if (d_->overlayVbo) glDeleteBuffers(1, &d_->overlayVbo);
  glDeleteQueries(3, d_->timers);
  for (GlProgram* p : {&d_->meshProg, &d_->pickProg, &d_->skyProg, &d_->gridProg, &d_->overlayProg,
                       &d_->tonemapProg, &d_->fxaaProg})
    p->release();
  d_ = std::make_unique<Impl>();
}

}  // namespace hs::render
