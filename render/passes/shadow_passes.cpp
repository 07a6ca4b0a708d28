#include "render/passes/shadow_passes.h"

#include <algorithm>
#include <cstring>

#include <glm/gtc/matrix_inverse.hpp>

#include "render/gpu_mesh_cache.h"
#include "render/mesh_lod.h"

namespace hs::render {
namespace {

// Slope-scaled and constant depth offset of the casters (glPolygonOffset,
// negative: away from the sun, whose side has the larger depth). The
// normal offset of the receivers (shaders/shadows.glsl) does most of the
// work; this removes the acne left on surfaces the sun grazes.
constexpr float kCasterSlopeOffset = -2.0f;
constexpr float kCasterConstantOffset = -4.0f;

struct Caster {
  const GpuMesh* mesh = nullptr;
  glm::dvec3 centre{0.0};  // frame-relative
  double radius = 0.0;
};

// Every mesh instance as a caster, at the level of detail the views draw
// (the same choice as visible_set.cpp, so a mesh shadows itself with its
// own triangles); object data relative to the frame origin. Casters are not
// limited to the views' frusta: a tree behind the camera shadows the
// ground in front of it.
void gatherCasters(const FrameContext& frame, std::vector<Caster>& casters, std::vector<GpuObject>& objects) {
  const glm::dvec3 origin = frame.visible.origin;
  for (const MeshInstanceRef& inst : frame.world.meshes) {
    const GpuMesh* g = frame.res.meshes.get(*inst.asset);
    if (!g) continue;
    const glm::dmat4& w = inst.world;
    const glm::dvec3 centre = glm::dvec3(w * glm::dvec4(glm::dvec3(g->bounds.center()), 1.0));
    const double maxScale = std::max({glm::length(glm::dvec3(w[0])), glm::length(glm::dvec3(w[1])),
                                      glm::length(glm::dvec3(w[2]))});
    if (!inst.asset->lods.empty()) {
      const MeshLodChoice lod = chooseMeshLod(inst.asset->lodErrors(), centre - frame.lodView.eye,
                                              double(g->bounds.radius()), maxScale, frame.lodView,
                                              frame.settings.meshLodErrorPixels);
      if (lod.level > 0)
        if (const GpuMesh* coarser = frame.res.meshes.get(*inst.asset, lod.level)) g = coarser;
    }
    glm::dmat4 rel = w;
    rel[3] = glm::dvec4(glm::dvec3(w[3]) - origin, 1.0);
    GpuObject o;
    o.model = glm::mat4(rel);
    o.normalMatrix = glm::mat4(glm::mat3(glm::inverseTranspose(glm::dmat3(w))));
    casters.push_back({g, centre - origin, double(g->bounds.radius()) * maxScale});
    objects.push_back(o);
  }
}

// Does a sphere (frame-relative) touch the cascade's box, open towards the sun?
bool touchesCascade(const ShadowCascade& c, const glm::dvec3& centre, double radius) {
  const glm::dvec4 clip = c.frameToClip * glm::dvec4(centre, 1.0);
  const double rx = radius / c.radius;
  return std::abs(clip.x) <= 1.0 + rx && std::abs(clip.y) <= 1.0 + rx && clip.z >= -0.5 * rx;
}

// The cascade's box as planes for the terrain's node culling (terrain_lod.h:
// relative to the LOD eye, the frame origin); the sun's side stays open.
Frustum cascadeVolume(const ShadowCascade& c) {
  const glm::dmat4& m = c.frameToClip;
  auto row = [&](int r) { return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
  Frustum f;
  f.planes[0] = row(3) + row(0);
  f.planes[1] = row(3) - row(0);
  f.planes[2] = row(3) + row(1);
  f.planes[3] = row(3) - row(1);
  f.planes[4] = row(2);                  // depth >= 0
  f.planes[5] = glm::dvec4(0, 0, 0, 1);  // no limit towards the sun
  for (int i = 0; i < 5; ++i) f.planes[i] /= glm::length(glm::dvec3(f.planes[i]));
  return f;
}

struct SunShadowData {
  TextureRef map;
  BufferRef views, casters;
  SunCascades cascades;
  std::vector<Caster> meshes;
  std::vector<GpuObject> objects;
  std::vector<std::vector<uint32_t>> perCascade;  // caster indices
  int resolution = 0;
};

size_t roundUpPow2(size_t v) {
  size_t p = 256;
  while (p < v) p *= 2;
  return p;
}

}  // namespace

void addShadowPasses(FrameGraph& graph, FrameContext& frame) {
  RenderResources& res = frame.res;
  ShadowResources& sh = res.shadows;
  GLint maxTexture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  std::string problem;
  const ShadowConfig config = resolveShadowConfig(frame.settings, maxTexture, &problem);
  if (!problem.empty() && problem != sh.problem) sh.newProblems.push_back(problem);
  sh.problem = problem;

  ShadowBlock block;
  sh.sun = {};
  if (config.enabled && frame.world.sun)
    sh.sun = computeSunCascades(frame.lodView, frame.world.sun->direction, config, frame.visible.origin);
  for (size_t i = 0; i < sh.sun.cascades.size(); ++i) {
    block.sunCascade[i] = glm::mat4(sh.sun.cascades[i].frameToMap);
    block.sunTexelMetres[int(i)] = float(sh.sun.cascades[i].texelMetres);
  }
  block.sunParams = glm::vec4(float(sh.sun.cascades.size()), float(config.pcfRadius), 1.0f / float(config.resolution), 0.0f);
  sh.block.upload(&block, sizeof block);
  glBindBufferRange(GL_UNIFORM_BUFFER, kShadowBlockBinding, sh.block.buffer.id(), 0, sizeof(ShadowBlock));
  if (sh.sun.cascades.empty()) return;

  const size_t viewStride = res.viewStride;
  const SunShadowData& data = graph.addPass<SunShadowData>(
      "shadow_sun",
      [&](PassBuilder& b, SunShadowData& d) {
        d.cascades = sh.sun;
        d.resolution = config.resolution;
        gatherCasters(frame, d.meshes, d.objects);
        d.perCascade.resize(d.cascades.cascades.size());
        for (size_t c = 0; c < d.cascades.cascades.size(); ++c)
          for (size_t i = 0; i < d.meshes.size(); ++i)
            if (touchesCascade(d.cascades.cascades[c], d.meshes[i].centre, d.meshes[i].radius))
              d.perCascade[c].push_back(uint32_t(i));
        const int layers = int(d.cascades.cascades.size());
        TextureDesc map{config.resolution, config.resolution, GL_DEPTH_COMPONENT32F, 1, layers};
        map.array = true;  // sampler2DArrayShadow, also for one cascade
        d.map = b.create("sun_shadow_map", map);
        d.views = b.create("sun_shadow_views", BufferDesc{roundUpPow2(size_t(layers) * viewStride)});
        if (!d.objects.empty())
          d.casters = b.create("sun_shadow_casters", BufferDesc{roundUpPow2(d.objects.size() * sizeof(GpuObject))});
      },
      [&frame, viewStride](const SunShadowData& d, const PassResources& r) {
        RenderResources& resources = frame.res;
        const GLuint map = r.texture(d.map);
        glTextureParameteri(map, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(map, GL_TEXTURE_COMPARE_FUNC, GL_GEQUAL);
        // One view block per cascade: the light's clip matrix as the
        // projection, no rotation or eye offset (positions are already
        // relative to the frame origin).
        const GLuint views = r.buffer(d.views);
        std::vector<uint8_t> blocks(d.cascades.cascades.size() * viewStride);
        for (size_t c = 0; c < d.cascades.cascades.size(); ++c) {
          ViewBlock vb;
          vb.projection = glm::mat4(d.cascades.cascades[c].frameToClip);
          vb.viewport = glm::vec4(float(d.resolution), float(d.resolution), 1.0f / float(d.resolution),
                                  1.0f / float(d.resolution));
          std::memcpy(blocks.data() + c * viewStride, &vb, sizeof vb);
        }
        glNamedBufferSubData(views, 0, GLsizeiptr(blocks.size()), blocks.data());
        if (d.casters.valid()) {
          resources.ensureObjectIndices(d.objects.size());
          glNamedBufferSubData(r.buffer(d.casters), 0, GLsizeiptr(d.objects.size() * sizeof(GpuObject)), d.objects.data());
          glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kObjectBufferBinding, r.buffer(d.casters));
        }
        glEnable(GL_DEPTH_CLAMP);  // casters beyond the sun's side of the box still cast
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(kCasterSlopeOffset, kCasterConstantOffset);
        glDisable(GL_CULL_FACE);   // open scans cast from both sides
        glViewport(0, 0, d.resolution, d.resolution);
        GlProgram& program = resources.program({"mesh.vert", "shadow_depth.frag", "", {}});
        for (size_t c = 0; c < d.cascades.cascades.size(); ++c) {
          glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({}, d.map, int(c)));
          const float clearDepth = 0.0f;
          glClearBufferfv(GL_DEPTH, 0, &clearDepth);
          glBindBufferRange(GL_UNIFORM_BUFFER, kViewBlockBinding, views, GLintptr(c * viewStride), sizeof(ViewBlock));
          program.use();
          for (uint32_t i : d.perCascade[c]) {
            const GpuMesh& m = *d.meshes[i].mesh;
            glBindVertexArray(m.vao);
            glDrawElementsInstancedBaseInstance(GL_TRIANGLES, GLsizei(m.data->indices.size()), GL_UNSIGNED_INT,
                                                nullptr, 1, i);
          }
          if (!frame.world.terrains.empty())
            resources.terrain.drawShadow(*frame.world.state, frame.world.terrains, frame.lodView,
                                   cascadeVolume(d.cascades.cascades[c]));
        }
        glDisable(GL_POLYGON_OFFSET_FILL);
        glDisable(GL_DEPTH_CLAMP);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kObjectBufferBinding, resources.objects.buffer.id());
      });
  frame.sunShadowMap = data.map;
}

void readShadowMaps(PassBuilder& b, const FrameContext& frame) {
  if (frame.sunShadowMap.valid()) b.read(frame.sunShadowMap);
}

void bindShadowMaps(const FrameContext& frame, const PassResources& r) {
  glBindTextureUnit(kShadowTextureUnit, frame.sunShadowMap.valid() ? r.texture(frame.sunShadowMap) : 0);
}

}  // namespace hs::render
