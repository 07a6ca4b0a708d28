#include "render/egl_context.h"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>

#include <epoxy/egl.h>

#include "render/gl/gl_debug.h"

namespace hs::render {
namespace {

std::string eglErrorName(EGLint e) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%04x", unsigned(e));
  switch (e) {
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    default: return buf;
  }
}

bool hasClientExtension(const char* name) {
  return epoxy_has_egl_extension(EGL_NO_DISPLAY, name);
}

// EGL hands every caller the same display for a platform, and
// eglTerminate() on it ends every context made on it: a display is
// terminated only when the last context of this process on it goes (two
// renderers at once: an export beside a preview, tests).
std::mutex displayUsersMutex;
std::map<void*, int> displayUsers;

}  // namespace

EglContext::~EglContext() { destroy(); }

bool EglContext::create(std::string& error) {
  EGLDisplay dpy = EGL_NO_DISPLAY;
  // HS_EGL_PLATFORM=device|surfaceless forces one (render nodes with both).
  const char* forced = std::getenv("HS_EGL_PLATFORM");
  const std::string want = forced ? forced : "";
  EGLint major = 0, minor = 0;
  auto tryDisplay = [&](EGLDisplay d, const char* name) {
    if (d == EGL_NO_DISPLAY) return false;
    if (!eglInitialize(d, &major, &minor)) return false;
    dpy = d;
    platform_ = name;
    return true;
  };
  if ((want.empty() || want == "surfaceless") && hasClientExtension("EGL_MESA_platform_surfaceless"))
    tryDisplay(eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr), "surfaceless");
  if (dpy == EGL_NO_DISPLAY && (want.empty() || want == "device") &&
      hasClientExtension("EGL_EXT_platform_device") && hasClientExtension("EGL_EXT_device_enumeration")) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (eglQueryDevicesEXT(16, devices, &count))
      for (EGLint i = 0; i < count && dpy == EGL_NO_DISPLAY; ++i)
        tryDisplay(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), "device");
  }
  if (dpy == EGL_NO_DISPLAY && want.empty()) tryDisplay(eglGetDisplay(EGL_DEFAULT_DISPLAY), "default");
  if (dpy == EGL_NO_DISPLAY) {
    error = "no EGL display: neither Mesa's surfaceless platform nor an EGL device is available "
            "(install libegl-mesa0 and libgl1-mesa-dri, or an NVIDIA driver with EGL)";
    return false;
  }
  display_ = dpy;
  {
    std::lock_guard lock(displayUsersMutex);
    ++displayUsers[display_];
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    error = "EGL (" + platform_ + "): desktop OpenGL is not available: " + eglErrorName(eglGetError());
    return false;
  }
  const EGLint configAttribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint n = 0;
  eglChooseConfig(dpy, configAttribs, &config, 1, &n);
  // A debug context when debug output is wanted (gl/gl_debug.h).
  const EGLint ctxAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_CONTEXT_OPENGL_DEBUG, gl::debugOutputRequested() ? EGL_TRUE : EGL_FALSE, EGL_NONE};
  // No config is fine where EGL_KHR_no_config_context exists: we draw into FBOs only.
  EGLContext ctx = eglCreateContext(dpy, n > 0 ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, ctxAttribs);
  if (ctx == EGL_NO_CONTEXT) {
    error = "EGL (" + platform_ + "): cannot create an OpenGL 4.5 core context: " + eglErrorName(eglGetError());
    return false;
  }
  context_ = ctx;
  if (!makeCurrent()) {
    error = "EGL (" + platform_ + "): cannot make the context current: " + eglErrorName(eglGetError());
    return false;
  }
  return true;
}

bool EglContext::makeCurrent() {
  return display_ && context_ && eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_);
}

void EglContext::destroy() {
  if (display_) {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_) eglDestroyContext(display_, context_);
    std::lock_guard lock(displayUsersMutex);
    if (--displayUsers[display_] <= 0) {
      displayUsers.erase(display_);
      eglTerminate(display_);
    }
  }
  display_ = context_ = nullptr;
}

}  // namespace hs::render
