#include "render/material_table.h"

#include <algorithm>
#include <cmath>

#include "mesh/alpha_coverage_mips.h"
#include "render/gpu_mesh_cache.h"
#include "render/render_resources.h"
#include "render/visible_set.h"
#include "scene/mesh_materials.h"

namespace hs::render {
namespace {

GpuMaterial gpuMaterialOf(const scene::Material& m) {
  GpuMaterial g;
  g.baseColor = glm::vec4(m.baseColor, m.opacity);
  g.emission = glm::vec4(m.emission * m.emissionStrength, m.alphaThreshold);
  g.surface = glm::vec4(m.roughness, m.metallic, m.specular, m.shininess);
  // Transmission only through two-sided surfaces: a one-sided one's back is culled.
  g.detail = glm::vec4(m.normalStrength, m.heightScale, m.twoSided ? m.transmission : 0.0f, 0.0f);
  uint32_t flags = 0;
  if (m.alphaCutout) flags |= kMatAlphaCutout;
  if (m.twoSided) flags |= kMatTwoSided;
  if (m.unlit) flags |= kMatUnlit;
  g.kind = glm::uvec4(uint32_t(m.model), flags, 0u, 0u);
  return g;
}

// A 2D texture of `levels` levels holding `t` as level 0, trilinear and
// repeating; the caller fills the levels below.
GLuint createTexture(const mesh::Texture& t, bool srgb, int levels) {
  GLuint tex = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &tex);
  glTextureStorage2D(tex, levels, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, t.width, t.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(tex, 0, 0, 0, t.width, t.height, GL_RGBA, GL_UNSIGNED_BYTE, t.rgba.data());
  glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return tex;
}

// `t` with the mip levels given (coverage-preserving ones for a cut-out).
// No anisotropic filter: its extra taps average alpha over the footprint
// as a coarser level would (on llvmpipe a leaf plane 16 px across kept a
// quarter of the cover the level holds), undoing what the levels keep.
GLuint uploadWithMips(const mesh::Texture& t, bool srgb, const std::vector<mesh::MipLevel>& mips) {
  const GLuint tex = createTexture(t, srgb, int(mips.size()) + 1);
  for (size_t i = 0; i < mips.size(); ++i)
    glTextureSubImage2D(tex, GLint(i + 1), 0, 0, mips[i].width, mips[i].height, GL_RGBA, GL_UNSIGNED_BYTE,
                        mips[i].rgba.data());
  return tex;
}

bool hasTransparency(const mesh::Texture& t) {
  for (size_t i = 3; i < t.rgba.size(); i += 4)
    if (t.rgba[i] != 255) return true;
  return false;
}

GLuint uploadStandalone(const mesh::Texture& t, bool srgb) {
  const GLuint tex =
      createTexture(t, srgb, 1 + int(std::floor(std::log2(double(std::max(t.width, t.height))))));
  glGenerateTextureMipmap(tex);
  return tex;
}

// A normal map stores x, y, z in red, green and blue: an image whose three
// channels are equal everywhere (a grey image, one channel expanded to
// RGBA on decoding) cannot be one.
bool isGrey(const mesh::Texture& t) {
  for (size_t i = 0; i + 3 < t.rgba.size(); i += 4)
    if (t.rgba[i] != t.rgba[i + 1] || t.rgba[i] != t.rgba[i + 2]) return false;
  return true;
}

}  // namespace

void MaterialTable::report(const std::string& problem) {
  if (reported_.insert(problem).second) problems_.push_back(problem);
}

std::vector<std::string> MaterialTable::takeProblems() {
  std::vector<std::string> out;
  out.swap(problems_);
  return out;
}

GLuint MaterialTable::cutoutTexture(scene::TextureId id, const std::shared_ptr<const mesh::Texture>& image, bool srgb,
                                    float threshold) {
  const int key = int(std::lround(std::clamp(threshold, 0.0f, 1.0f) * 255.0f));
  CutoutCopy& c = cutout_[{id, key}];
  if (c.image != image) {
    if (c.texture) glDeleteTextures(1, &c.texture);
    c = {};
    c.image = image;
    // An image opaque everywhere keeps its coverage at every level: no
    // copy (remembered, so the image is scanned once).
    if (hasTransparency(*image)) {
      c.texture = uploadWithMips(*image, srgb, mesh::coveragePreservingMips(*image, float(key) / 255.0f));
      c.bytes = size_t(image->width) * size_t(image->height) * 4 * 4 / 3;
    }
  }
  c.used = true;
  return c.texture;
}

GLuint MaterialTable::texture(const scene::SceneState& state, const scene::Material& m, const char* field,
                              scene::TextureId id, const GpuMesh& mesh, GpuMeshCache& meshes, bool normalMap,
                              float cutout) {
  if (id == scene::kNoTexture) return 0;
  const std::string where = "material '" + m.name + "': " + field + ": ";
  const scene::TextureAsset* t = state.findTexture(id);
  if (!t) {
    report(where + "texture " + std::to_string(id) + " is not in the scene; drawn without it");
    return 0;
  }
  const std::string named = where + "texture '" + t->name + "' ";
  const mesh::Texture* img = t->image.get();
  if (!img || img->width <= 0 || img->height <= 0) {
    report(named + "is empty (" + (img ? std::to_string(img->width) + "x" + std::to_string(img->height) : "no image") +
           "); drawn without it");
    return 0;
  }
  if (maxTextureSize_ <= 0) glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTextureSize_);
  if (img->width > maxTextureSize_ || img->height > maxTextureSize_) {
    report(named + "is " + std::to_string(img->width) + "x" + std::to_string(img->height) +
           ", larger than this GPU's limit of " + std::to_string(maxTextureSize_) + " pixels; drawn without it");
    return 0;
  }
  if (img->rgba.size() != size_t(img->width) * size_t(img->height) * 4) {
    report(named + "holds " + std::to_string(img->rgba.size()) + " bytes, not the " + std::to_string(img->width) +
           "x" + std::to_string(img->height) + "x4 of its size (damaged); drawn without it");
    return 0;
  }
  if (normalMap && isGrey(*img)) {
    report(named + "has one channel (grey); a normal map needs three (x, y, z in red, green, blue); drawn without it");
    return 0;
  }
  if (cutout > 0.0f && cutout < 1.0f)
    if (const GLuint copy = cutoutTexture(id, t->image, t->standalone() ? t->srgb : true, cutout)) return copy;
  if (!t->standalone()) {
    // The mesh's own upload (LOD levels share level 0's textures).
    const GpuMesh* owner = &mesh;
    if (t->asset != m.asset || mesh.textures.size() <= size_t(t->meshTexture)) {
      const scene::MeshAsset* a = state.findAsset(t->asset);
      owner = a ? meshes.get(*a) : nullptr;
    }
    if (!owner || size_t(t->meshTexture) >= owner->textures.size()) {
      report(named + "is missing from its mesh; drawn without it");
      return 0;
    }
    return owner->textures[size_t(t->meshTexture)];
  }
  Standalone& s = standalone_[id];
  if (s.texture && s.hash != t->contentHash) {
    glDeleteTextures(1, &s.texture);
    s = {};
  }
  if (!s.texture) {
    s.texture = uploadStandalone(*img, t->srgb);
    s.hash = t->contentHash;
    s.bytes = size_t(img->width) * size_t(img->height) * 4 * 4 / 3;
  }
  return s.texture;
}

void MaterialTable::build(const scene::SceneState& state, const std::vector<DrawItem>& draws,
                          std::pair<size_t, size_t> depthOnly, GpuMeshCache& meshes, GrowingBuffer& buffer) {
  block_.clear();
  byId_.clear();
  perDraw_.assign(draws.size(), {});
  std::map<std::pair<scene::AssetId, size_t>, DrawMaterial> fallbacks;
  std::map<scene::MaterialId, DrawMaterial> depthOnlyById;
  for (size_t d = 0; d < draws.size(); ++d) {
    const DrawItem& it = draws[d];
    const bool drawnLit = d < depthOnly.first || d >= depthOnly.second;
    const scene::MeshAsset* asset = it.asset;
    const mesh::MeshData& base = asset && asset->data ? *asset->data : *it.mesh->data;
    const auto& submeshes = it.mesh->data->submeshes;
    for (size_t s = 0; s < submeshes.size(); ++s) {
      const mesh::Submesh& sm = submeshes[s];
      // A material's entry is shared by the draws that use it; the UV range is the submesh's own.
      const glm::vec4 uvBounds = s < it.mesh->uvBounds.size() ? it.mesh->uvBounds[s] : glm::vec4(0.0f);
      const size_t slot = scene::materialSlotOf(base, sm);
      const scene::MaterialId id =
          asset && slot < asset->materialSlots.size() ? asset->materialSlots[slot] : scene::kNoMaterial;
      const scene::Material* m = state.findMaterial(id);
      if (m) {
        // A draw only shadow views draw needs the base colour of a
        // material that casts cut-out, nothing else: its own entry.
        std::map<scene::MaterialId, DrawMaterial>& cache = drawnLit ? byId_ : depthOnlyById;
        auto found = cache.find(id);
        if (found == cache.end()) {
          DrawMaterial dm;
          GpuMaterial g = gpuMaterialOf(*m);
          const bool castsCutout = m->alphaCutout || m->opacity < 1.0f;
          if (drawnLit || castsCutout)
            dm.textures[0] = texture(state, *m, "base_color_texture", m->baseColorTexture, *it.mesh, meshes, false,
                                     m->alphaCutout ? m->alphaThreshold : -1.0f);
          if (drawnLit) {
            dm.textures[1] = texture(state, *m, "normal_map", m->normalMap, *it.mesh, meshes, true);
            dm.textures[2] = texture(state, *m, "height_map", m->heightMap, *it.mesh, meshes, false);
          }
          // A base colour texture needs UVs to be sampled at all.
          if (!it.mesh->hasUvs) dm.textures[0] = dm.textures[1] = dm.textures[2] = 0;
          if (dm.textures[0]) g.kind.y |= kMatBaseTexture;
          if (dm.textures[1]) g.kind.y |= kMatNormalMap;
          if (dm.textures[2]) g.kind.y |= kMatHeightMap;
          dm.index = uint32_t(block_.size());
          dm.shading = m->shading;
          dm.twoSided = m->twoSided;
          dm.translucent = m->opacity < 1.0f && !m->alphaCutout;
          dm.castsCutout = castsCutout;
          dm.opacity = m->opacity;
          dm.alphaThreshold = m->alphaThreshold;
          const bool perPixel = m->shading != scene::ShadingMode::Gouraud;
          dm.normalMap = perPixel && dm.textures[1] != 0;
          dm.parallax = perPixel && dm.textures[2] != 0 && m->heightScale > 0.0f;
          block_.push_back(g);
          found = cache.emplace(id, dm).first;
        }
        // Tangents only for meshes a normal- or height-mapped material draws
        // in view (shadow casters draw depth alone).
        if (drawnLit && (found->second.normalMap || found->second.parallax)) meshes.addTangents(*it.mesh);
        perDraw_[d].push_back(found->second);
        perDraw_[d].back().uvBounds = uvBounds;
        continue;
      }
      // No document material (a state built in code, a slot past the list):
      // the mesh's own colour and texture with the defaults of a material.
      const auto key = std::make_pair(asset ? asset->id : scene::kNoAsset, slot);
      auto found = fallbacks.find(key);
      if (found == fallbacks.end()) {
        scene::Material def;
        DrawMaterial dm;
        if (slot < base.materials.size()) {
          const mesh::Material& src = base.materials[slot];
          def.baseColor = glm::vec3(src.baseColor);
          def.opacity = src.baseColor.a;
          if (src.diffuseTexture >= 0 && size_t(src.diffuseTexture) < it.mesh->textures.size() && it.mesh->hasUvs)
            dm.textures[0] = it.mesh->textures[size_t(src.diffuseTexture)];
        }
        GpuMaterial g = gpuMaterialOf(def);
        if (dm.textures[0]) g.kind.y |= kMatBaseTexture;
        dm.index = uint32_t(block_.size());
        dm.twoSided = def.twoSided;
        dm.translucent = def.opacity < 1.0f;
        block_.push_back(g);
        found = fallbacks.emplace(key, dm).first;
      }
      perDraw_[d].push_back(found->second);
      perDraw_[d].back().uvBounds = uvBounds;
    }
  }
  if (block_.empty()) block_.emplace_back();  // a buffer of zero bytes cannot be bound
  buffer.reserve(block_.size() * sizeof(GpuMaterial));
  buffer.upload(block_.data(), block_.size() * sizeof(GpuMaterial));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMaterialBufferBinding, buffer.buffer.id());
}

void MaterialTable::collect(const scene::SceneState& state) {
  // Cut-out copies the last frame did not use (the texture gone or
  // changed, the material no longer cut out or at another threshold).
  for (auto it = cutout_.begin(); it != cutout_.end();) {
    if (!it->second.used) {
      if (it->second.texture) glDeleteTextures(1, &it->second.texture);
      it = cutout_.erase(it);
    } else {
      it->second.used = false;
      ++it;
    }
  }
  for (auto it = standalone_.begin(); it != standalone_.end();) {
    const scene::TextureAsset* t = state.findTexture(it->first);
    if (!t || t->contentHash != it->second.hash) {
      glDeleteTextures(1, &it->second.texture);
      it = standalone_.erase(it);
    } else {
      ++it;
    }
  }
}

void MaterialTable::clear() {
  for (auto& [id, s] : standalone_) glDeleteTextures(1, &s.texture);
  standalone_.clear();
  for (auto& [key, c] : cutout_)
    if (c.texture) glDeleteTextures(1, &c.texture);
  cutout_.clear();
  perDraw_.clear();
  byId_.clear();
}

size_t MaterialTable::gpuBytes() const {
  size_t n = 0;
  for (const auto& [id, s] : standalone_) n += s.bytes;
  for (const auto& [key, c] : cutout_) n += c.bytes;
  return n;
}

}  // namespace hs::render
