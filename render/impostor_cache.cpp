#include "render/impostor_cache.h"

#include <algorithm>
#include <string>

#include "render/gpu_mesh_cache.h"
#include "render/impostor_atlas.h"
#include "render/render_resources.h"

namespace hs::render {
namespace {

constexpr int kAtlasPixels = kImpostorFrames * kImpostorFramePixels;
// Mip levels down to 4 pixels a frame: below that a texel would average
// neighbouring frames.
constexpr int kAtlasLevels = 5;
static_assert(kImpostorFramePixels >> (kAtlasLevels - 1) >= 4);

gl::Texture atlasTexture(GLenum format) {
  gl::Texture t = gl::createTexture(GL_TEXTURE_2D);
  glTextureStorage2D(t.id(), kAtlasLevels, format, kAtlasPixels, kAtlasPixels);
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t.id(), GL_TEXTURE_MAX_LEVEL, kAtlasLevels - 1);
  return t;
}

size_t atlasBytes() {
  size_t bytes = 0;
  for (int l = 0; l < kAtlasLevels; ++l) bytes += size_t(kAtlasPixels >> l) * size_t(kAtlasPixels >> l) * 4;
  return 2 * bytes;
}

}  // namespace

GLuint ImpostorCache::cardVao() {
  if (!cardVao_) {
    const uint32_t indices[6] = {0, 1, 2, 2, 1, 3};
    cardIndices_ = gl::createBuffer();
    glNamedBufferStorage(cardIndices_.id(), sizeof indices, indices, 0);
    cardVao_ = gl::createVertexArray();
    glVertexArrayElementBuffer(cardVao_.id(), cardIndices_.id());
  }
  return cardVao_.id();
}

ImpostorAtlas ImpostorCache::bake(RenderResources& res, uint64_t sourceKey, const GpuMesh& mesh,
                                  const std::vector<DrawMaterial>& materials) {
  ++bakes_;
  ImpostorAtlas atlas;
  atlas.sphere = glm::vec4(mesh.bounds.center(), mesh.bounds.radius());
  atlas.sourceKey = sourceKey;
  atlas.albedo = atlasTexture(GL_SRGB8_ALPHA8);
  atlas.normalDepth = atlasTexture(GL_RGBA8);
  atlas.bytes = atlasBytes();
  // The framebuffer and its depth (2.3 MB) live for the bake only: bakes
  // are rare, and nothing would count them while kept.
  const gl::Framebuffer fbo = gl::createFramebuffer();
  const gl::Texture depth = gl::createTexture(GL_TEXTURE_2D);
  glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, kAtlasPixels, kAtlasPixels);
  glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
  const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(fbo.id(), 2, buffers);
  glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, atlas.albedo.id(), 0);
  glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT1, atlas.normalDepth.id(), 0);

  // The state the frame had, given back after (a frame that bakes draws as
  // one that does not: test_impostors compares them).
  GLint framebuffer = 0, viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  glGetIntegerv(GL_VIEWPORT, viewport);
  const GLboolean culling = glIsEnabled(GL_CULL_FACE), depthTest = glIsEnabled(GL_DEPTH_TEST);
  GLint depthFunc = GL_LESS;
  GLboolean depthMask = GL_TRUE;
  glGetIntegerv(GL_DEPTH_FUNC, &depthFunc);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask);
  // The bake's depth is [0, 1] as a frame's (reversed): outside a frame
  // (Renderer::bakeImpostor) the context has GL's default [-1, 1].
  GLint clipOrigin = GL_LOWER_LEFT, clipDepth = GL_NEGATIVE_ONE_TO_ONE;
  glGetIntegerv(GL_CLIP_ORIGIN, &clipOrigin);
  glGetIntegerv(GL_CLIP_DEPTH_MODE, &clipDepth);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);

  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  const float zeros[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const float far = 0.0f;  // reversed depth
  glDepthMask(GL_TRUE);
  glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, zeros);
  glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 1, zeros);
  glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &far);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDisable(GL_CULL_FACE);  // a frame sees one-sided backs only behind fronts; leaf cards from both sides
  glEnable(GL_FRAMEBUFFER_SRGB);  // linear colour into the sRGB albedo
  GlProgram& p = res.program({"impostor_bake.vert", "impostor_bake.frag", "", {}});
  p.use();
  p.set("uSphere", atlas.sphere);
  glBindVertexArray(mesh.vao);
  const auto& subs = mesh.data->submeshes;
  for (int i = 0; i < kImpostorFrames; ++i)
    for (int j = 0; j < kImpostorFrames; ++j) {
      const glm::dvec3 d = impostorFrameDirection(i, j);
      const ImpostorBasis b = impostorBasis(d);
      glViewport(i * kImpostorFramePixels, j * kImpostorFramePixels, kImpostorFramePixels, kImpostorFramePixels);
      p.set("uFrameDir", glm::vec3(d));
      p.set("uFrameRight", glm::vec3(b.right));
      p.set("uFrameUp", glm::vec3(b.up));
      for (size_t s = 0; s < subs.size() && s < materials.size(); ++s) {
        const DrawMaterial& mat = materials[s];
        p.set("uMaterial", unsigned(mat.index));
        p.set("uUvBounds", mat.uvBounds);
        glBindTextureUnit(kMaterialTextureUnit, mat.textures[0]);
        glDrawElements(GL_TRIANGLES, GLsizei(subs[s].indexCount), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(uintptr_t(subs[s].firstIndex) * sizeof(uint32_t)));
      }
    }
  glDisable(GL_FRAMEBUFFER_SRGB);
  glGenerateTextureMipmap(atlas.albedo.id());
  glGenerateTextureMipmap(atlas.normalDepth.id());
  glBindTextureUnit(kMaterialTextureUnit, 0);
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(framebuffer));
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  if (culling) glEnable(GL_CULL_FACE);
  if (!depthTest) glDisable(GL_DEPTH_TEST);
  glDepthFunc(GLenum(depthFunc));
  glDepthMask(depthMask);
  glClipControl(GLenum(clipOrigin), GLenum(clipDepth));
  return atlas;
}

// Stored images of the current layout: level 0 uploaded, the mips rebuilt
// as after a bake. The pixel buffer bindings are cleared so the upload
// reads client memory whatever a pass left bound.
ImpostorAtlas ImpostorCache::upload(const foliage::ImpostorImages& images) {
  ImpostorAtlas atlas;
  atlas.sphere = images.sphere;
  atlas.sourceKey = images.sourceKey;
  atlas.stored = true;
  atlas.albedo = atlasTexture(GL_SRGB8_ALPHA8);
  atlas.normalDepth = atlasTexture(GL_RGBA8);
  atlas.bytes = atlasBytes();
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glTextureSubImage2D(atlas.albedo.id(), 0, 0, 0, kAtlasPixels, kAtlasPixels, GL_RGBA, GL_UNSIGNED_BYTE,
                      images.albedo.data());
  glTextureSubImage2D(atlas.normalDepth.id(), 0, 0, 0, kAtlasPixels, kAtlasPixels, GL_RGBA, GL_UNSIGNED_BYTE,
                      images.normalDepth.data());
  glGenerateTextureMipmap(atlas.albedo.id());
  glGenerateTextureMipmap(atlas.normalDepth.id());
  return atlas;
}

const ImpostorAtlas* ImpostorCache::get(RenderResources& res, const scene::MeshAsset& asset, uint64_t sourceKey,
                                        const GpuMesh& mesh, const std::vector<DrawMaterial>& materials) {
  if (mesh.bounds.empty || !(mesh.bounds.radius() > 0.0f) || !mesh.data) return nullptr;
  auto it = atlases_.find(asset.id);
  if (it != atlases_.end() && it->second.sourceKey == sourceKey) return &it->second;
  const foliage::ImpostorImages* stored = asset.impostor.get();
  const bool usable = stored && stored->sourceKey == sourceKey && stored->frames == kImpostorFrames &&
                      stored->framePixels == kImpostorFramePixels && stored->albedo.size() == stored->imageBytes() &&
                      stored->normalDepth.size() == stored->imageBytes();
  ImpostorAtlas& slot = atlases_[asset.id];
  if (usable) {
    ++uploads_;
    slot = upload(*stored);
  } else {
    slot = bake(res, sourceKey, mesh, materials);
  }
  return &slot;
}

std::optional<foliage::ImpostorImages> ImpostorCache::bakeAndRead(RenderResources& res, scene::AssetId asset,
                                                                  uint64_t sourceKey, const GpuMesh& mesh,
                                                                  const std::vector<DrawMaterial>& materials) {
  if (mesh.bounds.empty || !(mesh.bounds.radius() > 0.0f) || !mesh.data) return std::nullopt;
  ImpostorAtlas& slot = atlases_[asset];
  slot = bake(res, sourceKey, mesh, materials);
  foliage::ImpostorImages images;
  images.frames = kImpostorFrames;
  images.framePixels = kImpostorFramePixels;
  images.sphere = slot.sphere;
  images.sourceKey = sourceKey;
  images.albedo.resize(images.imageBytes());
  images.normalDepth.resize(images.imageBytes());
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  // The sRGB albedo is read through an RGBA8 view of it: its bytes as
  // stored (the upload writes them back as they are), where a read of the
  // sRGB texture itself may decode them to linear.
  GLuint view = 0;
  glGenTextures(1, &view);
  glTextureView(view, GL_TEXTURE_2D, slot.albedo.id(), GL_RGBA8, 0, 1, 0, 1);
  glGetTextureImage(view, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(images.albedo.size()), images.albedo.data());
  glDeleteTextures(1, &view);
  glGetTextureImage(slot.normalDepth.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(images.normalDepth.size()),
                    images.normalDepth.data());
  return images;
}

void ImpostorCache::collect(const scene::SceneState& state) {
  std::erase_if(atlases_, [&](const auto& kv) { return state.findAsset(kv.first) == nullptr; });
}

size_t ImpostorCache::gpuBytes() const {
  size_t n = 0;
  for (const auto& [id, a] : atlases_) n += a.bytes;
  return n;
}

}  // namespace hs::render
