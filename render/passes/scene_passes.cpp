#include "render/passes/scene_passes.h"

#include "render/fog_block.h"
#include "render/gpu_mesh_cache.h"
#include "render/passes/light_culling.h"
#include "render/passes/shadow_passes.h"

namespace hs::render {

gl::ProgramDesc meshProgramDesc(scene::ShadingMode mode, bool normalMap, bool parallax, bool debugNormal,
                                const std::vector<std::string>& extra) {
  gl::ProgramDesc d{"mesh.vert", "mesh.frag", "", extra};
  if (mode == scene::ShadingMode::Gouraud) d.defines.push_back("SHADING_GOURAUD");
  if (mode == scene::ShadingMode::Flat) d.defines.push_back("SHADING_FLAT");
  // Gouraud lights its vertices, some off screen where no cluster is: it
  // loops over every light of the frame.
  if (mode == scene::ShadingMode::Gouraud) std::erase(d.defines, std::string("LIGHTS_CLUSTERED"));
  if (mode != scene::ShadingMode::Gouraud) {
    if (normalMap || parallax) d.defines.push_back("HAS_TANGENTS");
    if (normalMap) d.defines.push_back("HAS_NORMAL_MAP");
    if (parallax) d.defines.push_back("HAS_PARALLAX");
    if (debugNormal) d.defines.push_back("DEBUG_SHADING_NORMAL");
  }
  return d;
}

SceneTargets addOpaquePass(FrameGraph& graph, FrameContext& frame, const ViewContext& v) {
  const int samples = frame.settings.antialiasing == scene::Antialiasing::Msaa4 ? 4 : 1;
  return graph.addPass<SceneTargets>(
      v.named("opaque"),
      [&](PassBuilder& b, SceneTargets& t) {
        // Linear HDR colour: RGBA16F; 32-bit float depth for reversed Z.
        t.samples = samples;
        t.color = b.create(v.named("scene_color"), TextureDesc{v.view.width, v.view.height, GL_RGBA16F, samples});
        t.depth = b.create(v.named("scene_depth"),
                           TextureDesc{v.view.width, v.view.height, GL_DEPTH_COMPONENT32F, samples});
        readShadowMaps(b, frame);
        readLightGrid(b, frame);
      },
      [&frame, index = v.index, w = v.view.width, h = v.view.height](const SceneTargets& t, const PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({t.color}, t.depth));
        glViewport(0, 0, w, h);
        const float clearColor[4] = {0, 0, 0, 1};
        const float clearDepth = 0.0f;
        glDepthMask(GL_TRUE);
        glClearBufferfv(GL_COLOR, 0, clearColor);
        glClearBufferfv(GL_DEPTH, 0, &clearDepth);
        if (frame.visible.draws.empty()) return;
        frame.res.bindView(index);
        bindShadowMaps(frame, r);
        bindLightGrid(frame, r, index);
        // One program per shading mode a material uses (shaders/mesh.frag's
        // variants), built on first use: none for modes nobody uses.
        GlProgram* programs[3][2][2] = {};
        const bool debugNormal = frame.options.debugShadingNormal;
        const std::vector<std::string> fog = surfaceDefines(frame);
        auto programFor = [&](const DrawMaterial& mat) -> GlProgram& {
          GlProgram*& p = programs[int(mat.shading)][mat.normalMap][mat.parallax];
          if (!p) p = &frame.res.program(meshProgramDesc(mat.shading, mat.normalMap, mat.parallax, debugNormal, fog));
          return *p;
        };
        GlProgram* current = nullptr;
        GLuint bound[3] = {0, 0, 0};
        int culling = -1;
        for (size_t d = 0; d < frame.visible.draws.size(); ++d) {
          const DrawItem& it = frame.visible.draws[d];
          glBindVertexArray(it.mesh->vao);
          const mesh::MeshData& m = *it.mesh->data;
          for (size_t s = 0; s < m.submeshes.size(); ++s) {
            const mesh::Submesh& sm = m.submeshes[s];
            const DrawMaterial& mat = frame.res.materials.forDraw(d, s);
            if (mat.translucent) continue;  // the transparency path draws it (render/oit.h)
            GlProgram& p = programFor(mat);
            if (&p != current) (current = &p)->use();
            p.set("uMaterial", unsigned(mat.index));
            for (unsigned u = 0; u < 3; ++u)
              if (mat.textures[u] && mat.textures[u] != bound[u]) glBindTextureUnit(kMaterialTextureUnit + u, bound[u] = mat.textures[u]);
            // One-sided materials cull their back faces; scans are seen from both sides.
            if (int(!mat.twoSided) != culling) {
              culling = int(!mat.twoSided);
              culling ? glEnable(GL_CULL_FACE) : glDisable(GL_CULL_FACE);
            }
            glDrawElementsInstancedBaseInstance(
                GL_TRIANGLES, GLsizei(sm.indexCount), GL_UNSIGNED_INT,
                reinterpret_cast<const void*>(uintptr_t(sm.firstIndex) * sizeof(uint32_t)), 1, it.object);
            frame.stats.trianglesDrawn += sm.indexCount / 3;
            ++frame.stats.drawCalls;
          }
          ++frame.stats.instancesDrawn;
        }
        glDisable(GL_CULL_FACE);
        for (unsigned u = 0; u < 3; ++u) glBindTextureUnit(kMaterialTextureUnit + u, 0);
      });
}

SceneTargets addTerrainPass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, const SceneTargets& targets) {
  struct Data {
    SceneTargets t;
  };
  return graph.addPass<Data>(
      v.named("terrain"),
      [&](PassBuilder& b, Data& d) {
        d.t = targets;
        d.t.color = b.write(b.read(targets.color));
        d.t.depth = b.write(b.read(targets.depth));
        readShadowMaps(b, frame);
        readLightGrid(b, frame);
      },
      [&frame, &view = v.view, index = v.index](const Data& d, const PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.t.color}, d.t.depth));
        frame.res.bindView(index);
        bindShadowMaps(frame, r);
        bindLightGrid(frame, r, index);
        const TerrainFrameStats ts =
            frame.res.terrain.draw(*frame.world.state, frame.world.terrains, view, frame.lodView,
                                   surfaceDefines(frame));
        frame.stats.trianglesDrawn += ts.triangles;
        frame.stats.drawCalls += ts.terrains;
        frame.stats.terrainTriangles += ts.triangles;
        frame.stats.terrainPatches += ts.patches;
        frame.stats.terrainUploadBytes += ts.upload.bytes;
        frame.stats.terrainUploadMs += ts.upload.cpuMs;
      }).t;
}

}  // namespace hs::render
