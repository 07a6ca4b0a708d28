#include "render/passes/scene_passes.h"

#include "render/gpu_mesh_cache.h"

namespace hs::render {

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
        GlProgram& p = frame.res.program({"mesh.vert", "mesh.frag", "", {}});
        p.use();
        GLuint bound = 0;
        for (const DrawItem& it : frame.visible.draws) {
          glBindVertexArray(it.mesh->vao);
          const mesh::MeshData& m = *it.mesh->data;
          for (const mesh::Submesh& sm : m.submeshes) {
            glm::vec4 color(0.8f, 0.8f, 0.8f, 1.0f);
            GLuint tex = 0;
            if (sm.material >= 0 && size_t(sm.material) < m.materials.size()) {
              const mesh::Material& mat = m.materials[size_t(sm.material)];
              color = mat.baseColor;
              if (mat.diffuseTexture >= 0 && size_t(mat.diffuseTexture) < it.mesh->textures.size() &&
                  it.mesh->hasUvs)
                tex = it.mesh->textures[size_t(mat.diffuseTexture)];
            }
            p.set("uBaseColor", color);
            p.set("uHasTexture", tex != 0);
            if (tex && tex != bound) glBindTextureUnit(0, bound = tex);
            glDrawElementsInstancedBaseInstance(
                GL_TRIANGLES, GLsizei(sm.indexCount), GL_UNSIGNED_INT,
                reinterpret_cast<const void*>(uintptr_t(sm.firstIndex) * sizeof(uint32_t)), 1, it.object);
            frame.stats.trianglesDrawn += sm.indexCount / 3;
            ++frame.stats.drawCalls;
          }
          ++frame.stats.instancesDrawn;
        }
        glBindTextureUnit(0, 0);
      });
}

void addTerrainPass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, const SceneTargets& targets) {
  struct Data {
    SceneTargets t;
  };
  graph.addPass<Data>(
      v.named("terrain"),
      [&](PassBuilder& b, Data& d) {
        d.t = targets;
        b.read(d.t.color);
        b.write(d.t.color);
        b.read(d.t.depth);
        b.write(d.t.depth);
      },
      [&frame, &view = v.view, index = v.index](const Data& d, const PassResources& r) {
        glBindFramebuffer(GL_FRAMEBUFFER, r.framebuffer({d.t.color}, d.t.depth));
        frame.res.bindView(index);
        const TerrainFrameStats ts =
            frame.res.terrain.draw(*frame.world.state, frame.world.terrains, view, frame.lodView);
        frame.stats.trianglesDrawn += ts.triangles;
        frame.stats.drawCalls += ts.terrains;
        frame.stats.terrainTriangles += ts.triangles;
        frame.stats.terrainPatches += ts.patches;
        frame.stats.terrainUploadBytes += ts.upload.bytes;
        frame.stats.terrainUploadMs += ts.upload.cpuMs;
      });
}

}  // namespace hs::render
