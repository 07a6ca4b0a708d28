#pragma once
// A chosen subset of a frame's mesh submeshes (the translucent ones, or
// every one) and how passes other than the opaque one draw it: with
// mesh.frag's variants per material, as the opaque pass draws, plus the
// pass's own defines (an A-buffer capture, a transparency mode), or with a
// fragment shader of the pass's own that needs no material (a counting
// pass). Include only inside render/.
#include <cstdint>
#include <string>
#include <vector>

#include "render/frame_context.h"

namespace hs::render {

struct SubmeshRef {
  uint32_t draw = 0;     // index into VisibleSet::draws
  uint32_t submesh = 0;  // into that draw's mesh's submeshes
};
using DrawList = std::vector<SubmeshRef>;

// Every submesh of the frame's visible meshes.
DrawList allSubmeshes(const VisibleSet& visible);

// Draws `list` into the bound framebuffer with the view's block already
// bound. With `fragment` empty, mesh.frag with the material's variants and
// `defines`; otherwise mesh.vert + `fragment` with `defines` alone.
// One-sided materials cull their back faces. Adds its draw calls to
// frame.stats; not its triangles: a list drawn by several passes (count,
// keys, lit) is one surface, which its owner counts once (triangleCount).
void drawSubmeshes(FrameContext& frame, const DrawList& list, const std::vector<std::string>& defines,
                   const std::string& fragment = "");

// The triangles of `list`.
size_t triangleCount(const FrameContext& frame, const DrawList& list);

}  // namespace hs::render
