#include "render/color_lut.h"

#include <OpenColorIO/OpenColorIO.h>

#include "scene/lut_processor.h"

namespace OCIO = OCIO_NAMESPACE;

namespace hs::render {
namespace {

// As OpenColorIO's own OpenGL helpers set them: nearest only where the
// LUT asks for it (its tetrahedral lookup reads texel centres itself).
void setSampling(GLuint texture, OCIO::Interpolation interpolation, bool volume) {
  const GLint filter = interpolation == OCIO::INTERP_NEAREST ? GL_NEAREST : GL_LINEAR;
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, filter);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, filter);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  if (volume) glTextureParameteri(texture, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
}

// `processor` as GLSL function `function` with its resources named from
// `prefix`; `name` (the LUT's or the config's) for messages.
std::unique_ptr<GpuLut> makeGpuTransform(const OCIO::ConstProcessorRcPtr& processor, const char* function,
                                         const char* prefix, const std::string& name, std::string& error) {
  if (!processor) return nullptr;
  auto out = std::make_unique<GpuLut>();
  try {
    OCIO::GpuShaderDescRcPtr desc = OCIO::GpuShaderDesc::CreateShaderDesc();
    desc->setLanguage(OCIO::GPU_LANGUAGE_GLSL_4_0);
    desc->setFunctionName(function);
    desc->setResourcePrefix(prefix);
    processor->getDefaultGPUProcessor()->extractGpuShaderInfo(desc);
    if (desc->getNumUniforms() != 0) {
      // A file transform has none; dynamic properties (exposure, contrast
      // of a config's look) are not what a stored transform can hold.
      error = name + ": OpenColorIO's shader for it needs uniforms (dynamic properties), which a stored "
                     "transform cannot have";
      return nullptr;
    }
    out->shaderText = desc->getShaderText();
    for (unsigned i = 0; i < desc->getNum3DTextures(); ++i) {
      const char *textureName = nullptr, *sampler = nullptr;
      unsigned edge = 0;
      OCIO::Interpolation interpolation = OCIO::INTERP_LINEAR;
      desc->get3DTexture(i, textureName, sampler, edge, interpolation);
      const float* values = nullptr;
      desc->get3DTextureValues(i, values);
      GpuLut::Table t{sampler, 0, GL_TEXTURE_3D, TextureDesc{}};
      t.desc.width = t.desc.height = t.desc.depth = int(edge);
      t.desc.format = GL_RGB32F;
      glCreateTextures(GL_TEXTURE_3D, 1, &t.texture);
      glTextureStorage3D(t.texture, 1, GL_RGB32F, GLsizei(edge), GLsizei(edge), GLsizei(edge));
      glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
      glTextureSubImage3D(t.texture, 0, 0, 0, 0, GLsizei(edge), GLsizei(edge), GLsizei(edge), GL_RGB, GL_FLOAT,
                          values);
      setSampling(t.texture, interpolation, true);
      out->bytes += t.desc.bytes();
      out->tables.push_back(std::move(t));
    }
    for (unsigned i = 0; i < desc->getNumTextures(); ++i) {
      const char *textureName = nullptr, *sampler = nullptr;
      unsigned width = 0, height = 0;
      OCIO::GpuShaderDesc::TextureType channel = OCIO::GpuShaderDesc::TEXTURE_RGB_CHANNEL;
      OCIO::Interpolation interpolation = OCIO::INTERP_LINEAR;
      desc->getTexture(i, textureName, sampler, width, height, channel, interpolation);
      const float* values = nullptr;
      desc->getTextureValues(i, values);
      const bool red = channel == OCIO::GpuShaderDesc::TEXTURE_RED_CHANNEL;
      const GLenum internal = red ? GL_R32F : GL_RGB32F, format = red ? GL_RED : GL_RGB;
      // OpenColorIO declares a table one texel high as a sampler1D.
      GpuLut::Table t{sampler, 0, height > 1 ? GLenum(GL_TEXTURE_2D) : GLenum(GL_TEXTURE_1D), TextureDesc{}};
      t.desc.width = int(width);
      t.desc.height = int(height);
      t.desc.format = internal;
      glCreateTextures(t.target, 1, &t.texture);
      if (t.target == GL_TEXTURE_2D) {
        glTextureStorage2D(t.texture, 1, internal, GLsizei(width), GLsizei(height));
        glTextureSubImage2D(t.texture, 0, 0, 0, GLsizei(width), GLsizei(height), format, GL_FLOAT, values);
      } else {
        glTextureStorage1D(t.texture, 1, internal, GLsizei(width));
        glTextureSubImage1D(t.texture, 0, 0, GLsizei(width), format, GL_FLOAT, values);
      }
      setSampling(t.texture, interpolation, false);
      out->bytes += t.desc.bytes();
      out->tables.push_back(std::move(t));
    }
  } catch (const std::exception& e) {
    error = name + ": OpenColorIO cannot make its GPU shader: " + e.what();
    for (const GpuLut::Table& t : out->tables) glDeleteTextures(1, &t.texture);
    return nullptr;
  }
  return out;
}

}  // namespace

const GpuLut* GpuLutCache::get(const scene::LutData& lut, std::string& error) {
  return cached(
      lut.fileName + '\n' + std::to_string(lut.contentHash),
      [&](std::string& e) {
        return makeGpuTransform(scene::lutProcessor(lut, e), "hsLut", "hs_lut_", lut.fileName, e);
      },
      lut.fileName, error);
}

const GpuLut* GpuLutCache::get(const scene::OcioConfigData& config, const std::string& display,
                               const std::string& view, std::string& error) {
  return cached(
      config.fileName + '\n' + std::to_string(config.contentHash) + '\n' + display + '\n' + view,
      [&](std::string& e) {
        return makeGpuTransform(scene::viewTransformProcessor(config, display, view, e), "hsView", "hs_view_",
                                config.fileName, e);
      },
      config.fileName, error);
}

const GpuLut* GpuLutCache::cached(const std::string& key,
                                  const std::function<std::unique_ptr<GpuLut>(std::string&)>& make,
                                  const std::string& name, std::string& error) {
  if (key_ == key && (lut_ || !failure_.empty())) {
    error = failure_;  // a transform that failed is not tried again every frame
    return lut_.get();
  }
  release();
  lut_ = make(error);
  key_ = key;
  if (!lut_) failure_ = error.empty() ? name + ": no GPU form" : error;
  return lut_.get();
}

void GpuLutCache::release() {
  if (lut_)
    for (const GpuLut::Table& t : lut_->tables) glDeleteTextures(1, &t.texture);
  lut_.reset();
  key_.clear();
  failure_.clear();
}

}  // namespace hs::render
