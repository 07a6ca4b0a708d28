#pragma once
// Headless OpenGL 4.5 core context through EGL, needing no X server: Mesa's
// surfaceless platform, or an EGL device (NVIDIA) where that is what there
// is. Rendering goes into framebuffer objects.
#include <string>

namespace hs::render {

class EglContext {
 public:
  EglContext() = default;
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  // False with `error` saying which step failed and what to check.
  bool create(std::string& error);
  bool makeCurrent();
  void destroy();
  // "surfaceless", "device" or "default": which EGL platform was used.
  const std::string& platform() const { return platform_; }

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string platform_;
};

}  // namespace hs::render
