#pragma once
// GPU copies of terrains, kept in step with the document's tiles through
// the terrain's change log (scene/terrain_data.h): a brush dab uploads only
// the region it changed, straight from the tiles (GL_UNPACK_ROW_LENGTH = the
// tile width, so nothing is repacked), and refreshes only the CDLOD bounds
// and LOD errors under it.
//
//   heights  R32F, one texel per sample (camera-relative maths happen in the
//            vertex shader; the texture holds heights relative to the origin)
//   holes    R8, only once the terrain has a hole
//   weights  RGBA8 array, four paint layers to a texel: a painted layer's
//            slice s is channel s % 4 of array layer s / 4, so the shader
//            reads every weight in (slices + 3) / 4 fetches instead of one a
//            layer (eight single-channel fetches were 70 of the demo
//            terrain's 550 ms a frame on llvmpipe). Only layers that have
//            painted tiles get a slice; the others are a constant (layer 0:
//            1, others: 0), so an unpainted terrain costs no weight memory.
//            The 16-bit weights are rounded to 8 bits while packing, as GL
//            converted them when it uploaded one layer a slice.
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include <epoxy/gl.h>

#include "render/terrain_lod.h"
#include "scene/scene_state.h"

namespace hs::render {

struct TerrainUploadStats {
  size_t bytes = 0;          // texel bytes handed to GL this frame
  size_t regions = 0;        // sub-image uploads
  double cpuMs = 0.0;        // uploads + bounds/LOD-error refresh
  double lodMs = 0.0;        // of which the CDLOD bounds and LOD errors
  bool full = false;         // everything was (re)uploaded
};

class GpuTerrain {
 public:
  void release();  // GL objects; not in a destructor, the context may be gone

  // Brings the GPU copy up to the data's change log. Returns what it did.
  TerrainUploadStats sync(const scene::TerrainData& data);

  GLuint heightTexture() const { return height_; }
  GLuint holesTexture() const { return holes_; }
  GLuint weightTexture() const { return weights_; }
  // Per layer: slice of the weights (channel slice % 4 of array layer
  // slice / 4), or -1 with constWeight().
  int weightSlice(int layer) const { return layer < int(slice_.size()) ? slice_[size_t(layer)] : -1; }
  // Array layers of weightTexture(): (slices + 3) / 4.
  int weightGroups() const { return (slices_ + 3) / 4; }
  float constWeight(int layer) const { return layer == 0 ? 1.0f : 0.0f; }
  const terrain::MinMaxTree& tree() const { return tree_; }
  const terrain::LodErrorMap& lodError() const { return error_; }
  int samplesX() const { return w_; }
  int samplesY() const { return h_; }
  size_t gpuBytes() const;

 private:
  void createHeights(const scene::TerrainData& data);
  void uploadHeights(const terrain::Heightfield& hf, const terrain::Region& r, TerrainUploadStats& s);
  void uploadHoles(const terrain::Heightfield& hf, const terrain::Region& r, TerrainUploadStats& s);
  void uploadWeights(const terrain::PaintLayers& paint, const terrain::Region& r, TerrainUploadStats& s);
  bool ensureHoles(const terrain::Heightfield& hf, TerrainUploadStats& s);
  bool ensureWeights(const terrain::PaintLayers& paint, TerrainUploadStats& s);

  uint64_t instance_ = 0;
  uint64_t serial_ = 0;
  int w_ = 0, h_ = 0;
  GLuint height_ = 0, holes_ = 0, weights_ = 0;
  std::vector<int> slice_;  // layer -> slice or -1
  int slices_ = 0;
  terrain::MinMaxTree tree_;
  terrain::LodErrorMap error_;
};

class GpuTerrainCache {
 public:
  // The GPU terrain for `data`, created and synced as needed.
  GpuTerrain* get(const scene::TerrainData& data, TerrainUploadStats* stats = nullptr);
  // Frees terrains no longer in `state`.
  void collect(const scene::SceneState& state);
  void clear();
  size_t gpuBytes() const;

 private:
  std::map<uint64_t, std::unique_ptr<GpuTerrain>> terrains_;  // by TerrainData::instance()
};

}  // namespace hs::render
