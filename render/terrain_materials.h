#pragma once
// Texture arrays for terrain materials (albedo and normal maps), one slice
// per material that names a texture, every image resampled to one size so
// a single sampler serves all layers (a sampler per material would exceed
// the 32 texture units llvmpipe offers once there are 16 layers). Rebuilt
// only when the list of texture paths changes. A file that cannot be read
// leaves that material on its colour alone and is reported once per rebuild
// (update() returns it, naming the material and the file).
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "terrain/paint_layers.h"

namespace hs::render {

class TerrainMaterialTextures {
 public:
  static constexpr int kSize = 512;  // texels per side of every slice

  void release();
  // Brings the arrays in line with `materials`' texture paths. Returns the
  // files this call could not read ("material 'Grass': albedo texture
  // PATH: reason"); empty when nothing was rebuilt.
  std::vector<std::string> update(const std::vector<terrain::Material>& materials);
  GLuint albedo() const { return albedo_; }
  GLuint normal() const { return normal_; }
  // Slice of material i's albedo / normal map, or -1.
  int albedoSlice(int i) const { return i < int(albedoSlice_.size()) ? albedoSlice_[size_t(i)] : -1; }
  int normalSlice(int i) const { return i < int(normalSlice_.size()) ? normalSlice_[size_t(i)] : -1; }
  // Files of the current arrays that could not be read (as update() words them).
  std::vector<std::string> problems() const;
  size_t gpuBytes() const;

 private:
  GLuint build(const std::vector<std::string>& paths, const std::vector<std::string>& names, bool normal,
               std::vector<int>& slices, std::vector<std::string>& problems);
  std::vector<std::string> albedoPaths_, normalPaths_;
  std::vector<int> albedoSlice_, normalSlice_;
  GLuint albedo_ = 0, normal_ = 0;
  int albedoSlices_ = 0, normalSlices_ = 0;
  std::vector<std::string> albedoProblems_, normalProblems_;
};

}  // namespace hs::render
