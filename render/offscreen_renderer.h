#pragma once
// Headless rendering for the CLI, tests and render nodes: an EGL context, the
// renderer and an output framebuffer, rendering a scene to a CPU image.
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "render/renderer.h"

namespace hs::render {

class OffscreenRenderer {
 public:
  OffscreenRenderer();
  ~OffscreenRenderer();

  // Creates the EGL context and the renderer. False with `error` if there is
  // no usable GL.
  bool initialize(std::string& error);
  std::string glDescription() const { return glDescription_; }
  const std::string& eglPlatform() const;
  // Makes the context current on the calling thread (for render/ code that
  // draws through renderer() into its own buffers).
  bool makeCurrent();

  // Renders `view` and reads it back: 8-bit sRGB, or linear float with `hdr`.
  Image render(const scene::SceneState& state, const RenderView& view, bool hdr = false,
               FrameStats* stats = nullptr, const RenderOptions& options = {});
  // Several shots in one frame (Renderer::renderGroups), mixed by
  // `weights` (one per view) into one image, read back like render()'s.
  // `pattern`'s transition, progress and frame (not its targets or
  // weights) combine the first two by a patterned transition instead.
  Image renderMix(const scene::SceneState& state, const std::vector<RenderView>& views,
                  const std::vector<float>& weights, bool hdr = false, FrameStats* stats = nullptr,
                  const RenderOptions& options = {}, const GroupCombine* pattern = nullptr);
  // Renders without reading back (benchmarks of the GPU side); waits for the GPU.
  FrameStats renderOnly(const scene::SceneState& state, const RenderView& view, const RenderOptions& options = {});
  // The same for several views of one frame (Renderer::renderViews: the two
  // eyes of a stereo pair, eye-independent work done once), each into its
  // own target; waits for the GPU. All views must have the same size.
  FrameStats renderViewsOnly(const scene::SceneState& state, const std::vector<RenderView>& views,
                             const RenderOptions& options = {});
  Renderer& renderer();

 private:
  struct Impl;
  std::unique_ptr<Impl> d_;
  std::string glDescription_;
};

}  // namespace hs::render
