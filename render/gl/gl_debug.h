#pragma once
// OpenGL's debug output (KHR_debug), routed to the editor's Messages and the
// CLI's stderr instead of lost. On in debug builds and whenever HS_GL_DEBUG
// is set (HS_GL_DEBUG=2 also keeps low-severity notes); the context is then
// made a debug context (egl_context.cpp, app_settings.cpp), which drivers
// need for full reports.
#include <mutex>
#include <string>
#include <vector>

namespace hs::render::gl {

// Whether debug output is wanted in this process.
bool debugOutputRequested();

// Collects the messages of the current context's debug callback.
class DebugMessages {
 public:
  // Installs the callback on the current context (a no-op when not
  // requested or when the context has no KHR_debug).
  void install();
  std::vector<std::string> take();

 private:
  static void callback(unsigned source, unsigned type, unsigned id, unsigned severity, int length,
                       const char* message, const void* user);
  std::mutex mutex_;
  std::vector<std::string> messages_;
  bool lowSeverity_ = false;
};

}  // namespace hs::render::gl
