#include "render/gl/gl_debug.h"

#include <cstdlib>
#include <cstring>

#include <epoxy/gl.h>

namespace hs::render::gl {

bool debugOutputRequested() {
#ifndef NDEBUG
  return true;
#else
  const char* v = std::getenv("HS_GL_DEBUG");
  return v && *v && std::strcmp(v, "0") != 0;
#endif
}

void DebugMessages::install() {
  if (!debugOutputRequested()) return;
  if (epoxy_gl_version() < 43 && !epoxy_has_gl_extension("GL_KHR_debug")) return;
  const char* v = std::getenv("HS_GL_DEBUG");
  lowSeverity_ = v && std::strcmp(v, "2") == 0;
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);  // messages arrive on the thread that caused them
  glDebugMessageCallback(reinterpret_cast<GLDEBUGPROC>(&DebugMessages::callback), this);
}

void DebugMessages::callback(unsigned source, unsigned type, unsigned, unsigned severity, int length,
                             const char* message, const void* user) {
  auto* self = static_cast<DebugMessages*>(const_cast<void*>(user));
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION || (severity == GL_DEBUG_SEVERITY_LOW && !self->lowSeverity_))
    return;
  const char* kind = type == GL_DEBUG_TYPE_ERROR                 ? "error"
                     : type == GL_DEBUG_TYPE_PERFORMANCE         ? "performance"
                     : type == GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR ? "deprecated"
                     : type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR  ? "undefined behaviour"
                                                                 : "note";
  const char* from = source == GL_DEBUG_SOURCE_SHADER_COMPILER ? "shader compiler"
                     : source == GL_DEBUG_SOURCE_API           ? "API"
                                                               : "driver";
  std::string text = std::string("OpenGL ") + kind + " (" + from + "): " +
                     std::string(message, length >= 0 ? size_t(length) : std::strlen(message));
  std::lock_guard lock(self->mutex_);
  if (self->messages_.size() < 1000) self->messages_.push_back(std::move(text));
}

std::vector<std::string> DebugMessages::take() {
  std::lock_guard lock(mutex_);
  std::vector<std::string> out;
  out.swap(messages_);
  return out;
}

}  // namespace hs::render::gl
