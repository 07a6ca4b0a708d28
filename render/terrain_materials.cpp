#include "render/terrain_materials.h"

#include <algorithm>
#include <cmath>

#include "mesh/texture_decode.h"

namespace hs::render {
namespace {

// Bilinear resample of an RGBA8 image to kSize^2 (textures repeat, so the
// sampling wraps).
std::vector<uint8_t> resample(const mesh::Texture& t, int size) {
  std::vector<uint8_t> out(size_t(size) * size_t(size) * 4);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double u = (x + 0.5) * t.width / size - 0.5, v = (y + 0.5) * t.height / size - 0.5;
      const int x0 = int(std::floor(u)), y0 = int(std::floor(v));
      const double fx = u - x0, fy = v - y0;
      for (int c = 0; c < 4; ++c) {
        auto at = [&](int xx, int yy) {
          xx = ((xx % t.width) + t.width) % t.width;
          yy = ((yy % t.height) + t.height) % t.height;
          return double(t.rgba[(size_t(yy) * size_t(t.width) + size_t(xx)) * 4 + size_t(c)]);
        };
        const double val = (at(x0, y0) * (1 - fx) + at(x0 + 1, y0) * fx) * (1 - fy) +
                           (at(x0, y0 + 1) * (1 - fx) + at(x0 + 1, y0 + 1) * fx) * fy;
        out[(size_t(y) * size_t(size) + size_t(x)) * 4 + size_t(c)] = uint8_t(std::clamp(std::lround(val), 0L, 255L));
      }
    }
  return out;
}

}  // namespace

void TerrainMaterialTextures::release() {
  GLuint t[2] = {albedo_, normal_};
  glDeleteTextures(2, t);
  albedo_ = normal_ = 0;
  albedoPaths_.clear();
  normalPaths_.clear();
  albedoSlice_.clear();
  normalSlice_.clear();
}

size_t TerrainMaterialTextures::gpuBytes() const {
  return size_t(albedoSlices_ + normalSlices_) * size_t(kSize) * size_t(kSize) * 4 * 4 / 3;
}

std::vector<std::string> TerrainMaterialTextures::problems() const {
  std::vector<std::string> out = albedoProblems_;
  out.insert(out.end(), normalProblems_.begin(), normalProblems_.end());
  return out;
}

GLuint TerrainMaterialTextures::build(const std::vector<std::string>& paths, const std::vector<std::string>& names,
                                      bool normal, std::vector<int>& slices, std::vector<std::string>& problems) {
  const bool srgb = !normal;  // colour is sRGB-encoded; normal maps are data
  problems.clear();
  slices.assign(paths.size(), -1);
  std::vector<std::vector<uint8_t>> images;
  for (size_t i = 0; i < paths.size(); ++i) {
    if (paths[i].empty()) continue;
    mesh::Texture t;
    std::string error;
    if (!mesh::decodeTextureFile(paths[i], t, error) || t.width <= 0 || t.height <= 0) {
      problems.push_back("material '" + names[i] + "': " + (normal ? "normal map " : "albedo texture ") + paths[i] +
                         ": " + (error.empty() ? "cannot be read" : error));
      continue;
    }
    slices[i] = int(images.size());
    images.push_back(resample(t, kSize));
  }
  if (images.empty()) return 0;
  GLuint tex = 0;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &tex);
  const int levels = 1 + int(std::log2(double(kSize)));
  glTextureStorage3D(tex, levels, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, kSize, kSize, GLsizei(images.size()));
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (size_t i = 0; i < images.size(); ++i)
    glTextureSubImage3D(tex, 0, 0, 0, GLint(i), kSize, kSize, 1, GL_RGBA, GL_UNSIGNED_BYTE, images[i].data());
  glGenerateTextureMipmap(tex);
  glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return tex;
}

std::vector<std::string> TerrainMaterialTextures::update(const std::vector<terrain::Material>& materials) {
  std::vector<std::string> albedo, normal, names, found;
  for (const auto& m : materials) {
    albedo.push_back(m.albedoTexture);
    normal.push_back(m.normalTexture);
    names.push_back(m.name);
  }
  if (albedo != albedoPaths_) {
    if (albedo_) glDeleteTextures(1, &albedo_);
    albedo_ = build(albedo, names, false, albedoSlice_, albedoProblems_);
    found.insert(found.end(), albedoProblems_.begin(), albedoProblems_.end());
    albedoSlices_ = int(std::count_if(albedoSlice_.begin(), albedoSlice_.end(), [](int s) { return s >= 0; }));
    albedoPaths_ = albedo;
  }
  if (normal != normalPaths_) {
    if (normal_) glDeleteTextures(1, &normal_);
    normal_ = build(normal, names, true, normalSlice_, normalProblems_);
    found.insert(found.end(), normalProblems_.begin(), normalProblems_.end());
    normalSlices_ = int(std::count_if(normalSlice_.begin(), normalSlice_.end(), [](int s) { return s >= 0; }));
    normalPaths_ = normal;
  }
  return found;
}

}  // namespace hs::render
