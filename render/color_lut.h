#pragma once
// The GPU side of OpenColorIO's colour transforms held by the document: a
// grading LUT (scene/color_lut.h) and a config's display/view transform
// (scene/ocio_config.h). OpenColorIO's shader generator writes a GLSL
// function for the processor and the tables it samples (3D textures for 3D
// LUTs, 1D/2D ones for 1D LUTs and shapers); a cache makes the textures
// once per transform and keeps them while it is in use. The tone map pass
// (passes/output_passes.cpp) puts the functions into its program and
// imports the 3D and 2D textures into the frame graph. Include only inside
// render/.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "render/resource_pool.h"
#include "scene/scene_state.h"

namespace hs::render {

struct GpuLut {
  // OpenColorIO's GLSL: its sampler uniforms and the function (`vec4
  // hsLut(vec4)` for a LUT, `vec4 hsView(vec4)` for a view transform).
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

  // The GPU form of `lut` as `hsLut` (made on first use; the last one
  // made is kept, any other freed). Null with `error` when OpenColorIO
  // cannot make it (the LUT was checked on import and on load, so this is
  // rare).
  const GpuLut* get(const scene::LutData& lut, std::string& error);
  // The GPU form of `config`'s display/view transform (empty names: the
  // config's defaults) as `hsView`; null with `error` naming the config
  // and the display or view at fault.
  const GpuLut* get(const scene::OcioConfigData& config, const std::string& display, const std::string& view,
                    std::string& error);
  void release();
  // The kept transform's texture memory (the renderer's registry lists it).
  size_t gpuBytes() const { return lut_ ? lut_->bytes : 0; }

 private:
  const GpuLut* cached(const std::string& key, const std::function<std::unique_ptr<GpuLut>(std::string&)>& make,
                       const std::string& name, std::string& error);
  std::string key_;      // what the kept transform was made from (name, hash, display, view)
  std::unique_ptr<GpuLut> lut_;
  std::string failure_;  // why the GPU form of that transform could not be made
};

}  // namespace hs::render
