#pragma once
// The GPU side of a grading LUT (scene/color_lut.h): OpenColorIO's shader
// generator writes a GLSL function for the LUT's processor and the tables
// it samples (3D textures for 3D LUTs, 1D/2D ones for 1D LUTs and
// shapers); this cache makes the textures once per LUT and keeps them
// while the LUT is in use. The tone map pass (passes/output_passes.cpp)
// puts the function into its program and imports the 3D and 2D textures
// into the frame graph. Include only inside render/.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "render/resource_pool.h"
#include "scene/scene_state.h"

namespace hs::render {

struct GpuLut {
  // OpenColorIO's GLSL: its sampler uniforms and `vec4 hsLut(vec4)`.
  std::string shaderText;
  struct Table {
    std::string sampler;  // the uniform OpenColorIO named it
    GLuint texture = 0;   // owned by the cache
    GLenum target = GL_TEXTURE_3D;
    TextureDesc desc{};   // for the frame graph (3D and 2D tables)
  };
  std::vector<Table> tables;
  size_t bytes = 0;       // texture memory
};

class GpuLutCache {
 public:
  GpuLutCache() = default;
  ~GpuLutCache() { release(); }
  GpuLutCache(const GpuLutCache&) = delete;
  GpuLutCache& operator=(const GpuLutCache&) = delete;

  // The GPU form of `lut` (made on first use; the last one made is kept,
  // any other freed). Null with `error` when OpenColorIO cannot make it
  // (the LUT was checked on import and on load, so this is rare).
  const GpuLut* get(const scene::LutData& lut, std::string& error);
  void release();
  // The kept LUT's texture memory (the renderer's registry lists it).
  size_t gpuBytes() const { return lut_ ? lut_->bytes : 0; }

 private:
  uint64_t hash_ = 0;
  std::string fileName_;
  std::unique_ptr<GpuLut> lut_;
  std::string failure_;  // why the GPU form of that LUT could not be made
};

}  // namespace hs::render
