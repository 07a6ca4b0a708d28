#pragma once
// One full-screen triangle (shaders/fullscreen.vert) with a fragment
// shader: the setup every post pass needs (program, inputs, target,
// viewport, depth test off, draw, inputs unbound) written once. Include
// only inside render/.
//
// drawFullscreen is the draw alone, for a pass that does more around it
// (blending, a loop of peels); addFullscreenPass is a whole pass of the
// frame graph: it reads its inputs, creates its output (or draws into the
// view's own framebuffer) and draws.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "render/frame_context.h"

namespace hs::render {

struct FullscreenDraw {
  std::string fragment;                          // "tonemap.frag"
  std::vector<std::string> defines{};
  std::string generated{};                       // gl::ProgramDesc::generated
  GLuint framebuffer = 0;
  int width = 0, height = 0;                     // the viewport
  std::vector<std::pair<unsigned, GLuint>> textures{};  // (texture unit, texture)
  std::function<void(GlProgram&)> uniforms{};    // set after the program is chosen
  int view = -1;                                 // >= 0: binds that view's block first
  // 0: no depth test. Else the test against the framebuffer's depth, not
  // writing it (the sky: GL_EQUAL where the cleared far value is left).
  GLenum depthFunc = 0;
  // With depthFunc: write the depth too (a mask that a later pass's
  // GL_EQUAL test shades only where this one drew: SMAA's edge pixels).
  bool depthWrite = false;
};
// Leaves the depth test on, writing, GL_GREATER (the frame's default) and
// blending as it was. Needs only the renderer's resources, so paths outside
// a frame graph (the lens-sampled DoF reference's accumulation) use it too.
void drawFullscreen(RenderResources& res, const FullscreenDraw& draw);

struct FullscreenPass {
  std::string name;                   // the pass's name, with the view's suffix
  std::string fragment;
  std::vector<std::string> defines{};
  std::string generated{};
  std::vector<std::pair<unsigned, TextureRef>> inputs{};  // (texture unit, what it samples)
  // The output: a new texture `outputName` of `output`, or with `toTarget`
  // the view's framebuffer (a side effect) at the view's size.
  std::string outputName{};
  TextureDesc output{};
  bool toTarget = false;
  std::function<void(GlProgram&)> uniforms{};
  bool bindView = false;
};
// Returns the output texture (invalid with toTarget).
TextureRef addFullscreenPass(FrameGraph& graph, FrameContext& frame, const ViewContext& v, FullscreenPass pass);

}  // namespace hs::render
