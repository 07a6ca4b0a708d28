#pragma once
// A kind of geometry the frame draws (docs/architecture.md "How to add a
// kind of geometry"): meshes (mesh_source.h) and terrains
// (terrain_source.h) now; foliage, particles and cluster hierarchies are
// each one more source, not a fifth copy of "draw the meshes". Every pass
// that draws the scene (the lit opaque pass, each shadow view, picking, the
// transparency passes, the layered depth of field's capture) asks each of
// the frame's sources for its draws of one variant; a source records them
// from CPU lists or from indirect command buffers a compute pass wrote.
// Include only inside render/.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "render/frame_graph.h"
#include "render/render_view.h"
#include "scene/ids.h"

namespace hs::render {

struct FrameContext;
struct DrawItem;

enum class DrawVariant : uint8_t {
  // Into a camera view: with each material's program (shaders/mesh.frag's
  // variants and DrawCall::defines), or with a pass's own fragment shader
  // that needs no material (DrawCall::fragment: the A-buffer's count and
  // keys, the K-buffer's depth pass).
  Surface,
  // Depth only into a shadow view (DrawCall::shadowView), with the alpha
  // cut-out and the hashed translucency of shaders/shadow_depth.frag.
  Depth,
  // A uint id per pixel for viewport picking (DrawCall::pickBase onwards).
  Pick,
};

// Which of a source's surfaces a Surface draw asks for.
enum class SurfaceSet : uint8_t {
  Opaque,       // the lit opaque pass
  Translucent,  // opacity under 1, no cut-out: the transparency passes (render/oit.h)
  All,          // every surface, hidden ones too (the layered depth of field's capture)
};

struct DrawCall {
  DrawVariant variant = DrawVariant::Surface;
  SurfaceSet surfaces = SurfaceSet::Opaque;
  size_t view = 0;                   // Surface, Pick: the camera view whose block is bound
  std::vector<std::string> defines{};  // Surface: the program's variant
  std::string fragment{};            // Surface: a pass's fragment shader (empty: the material's)
  size_t shadowView = 0;             // Depth: index into FrameContext::shadowViews
  uint32_t pickBase = 0;             // Pick: this source's first id
  // Pick: the pixel of the view the 1x1 id target stands for, from its
  // lower left (screen-space dithers, shaders/instance_fade.glsl, follow it).
  glm::ivec2 pickPixel{0};
};

// What a pick id names: an entity and, for an instanced source, the
// instance's stable id within it.
struct PickedItem {
  scene::EntityId entity = scene::kNoEntity;
  uint32_t instance = UINT32_MAX;  // UINT32_MAX: the entity as a whole
};

class DrawSource {
 public:
  virtual ~DrawSource() = default;
  // Its lit pass's name when it has one of its own ("terrain"); empty: it
  // draws in the opaque pass, which creates and clears the targets.
  virtual std::string ownPass() const { return {}; }
  // Whether it has anything for this variant (and surface set), decided at
  // setup: a pass nothing draws into is not added (no transparency pass
  // without a translucent surface).
  virtual bool has(DrawVariant variant, SurfaceSet surfaces = SurfaceSet::Opaque) const = 0;
  // The frame's shadow views [first, first + count) of FrameContext::
  // shadowViews are known: choose the casters of each, once, from the same
  // bounds and level of detail the camera views use.
  virtual void cullShadowViews(FrameContext& frame, size_t first, size_t count) {
    (void)frame, (void)first, (void)count;
  }
  // Appends the draws (mesh and asset) whose materials its draws use; the
  // frame's MaterialTable resolves them with the meshes' own, and
  // forDraw(i, submesh) answers for the i-th entry of `draws`.
  virtual void addMaterials(FrameContext& frame, std::vector<DrawItem>& draws) { (void)frame, (void)draws; }
  // Adds the passes that prepare its draws (a compute pass filling indirect
  // commands) before the first pass that draws it.
  virtual void addPreparePasses(FrameGraph& graph, FrameContext& frame) { (void)graph, (void)frame; }
  // Declares, in a drawing pass's setup, what its draws read (its instance
  // and indirect buffers), so the graph orders and fences them.
  virtual void declare(PassBuilder& builder, DrawVariant variant) const { (void)builder, (void)variant; }
  // Records its draws of `call` into the bound framebuffer; the frame's
  // blocks and the view are bound. Adds its draw calls to frame.stats.
  virtual void draw(FrameContext& frame, const DrawCall& call, const PassResources& resources) = 0;
  // Triangles of one drawing of `surfaces` (a surface drawn by several
  // passes, count, keys and lit, is counted once by its owner).
  virtual size_t triangles(SurfaceSet surfaces) const { (void)surfaces; return 0; }
  // The nearest depth (metres along `view`'s axis) of what it draws into
  // `view`, after its setup: the depth of field sizes its largest blur from
  // it (passes/dof_passes.h). +inf: nothing near (the default; a terrain's
  // reach to the camera is the world's, RenderWorld::terrains).
  virtual double nearestDepth(const RenderView& view) const { (void)view; return INFINITY; }
  // Picking: the ids it writes (pickBase .. pickBase + pickIds() - 1) and
  // what id pickBase + k names.
  virtual uint32_t pickIds() const { return 0; }
  virtual PickedItem picked(uint32_t k) const { (void)k; return {}; }
};

// Calls every source of the frame that has `call`'s variant.
void drawSources(FrameContext& frame, const DrawCall& call, const PassResources& resources);
// A Surface draw of `surfaces` of every source into camera view `view`:
// with the materials' programs and `defines`, or with `fragment`.
void drawSurfaces(FrameContext& frame, const PassResources& resources, size_t view, SurfaceSet surfaces,
                  std::vector<std::string> defines, std::string fragment = {});
// Declares every source that has `variant` in a pass's setup.
void declareSources(PassBuilder& builder, const FrameContext& frame, DrawVariant variant,
                    SurfaceSet surfaces = SurfaceSet::Opaque);
// Does any source of the frame have it?
bool anySource(const FrameContext& frame, DrawVariant variant, SurfaceSet surfaces = SurfaceSet::Opaque);
// Triangles of `surfaces` over the frame's sources.
size_t sourceTriangles(const FrameContext& frame, SurfaceSet surfaces);
// Appends shadow views (volumes relative to the frame origin) and lets every
// source cull its casters for them; returns the first one's index.
size_t addShadowViews(FrameContext& frame, const std::vector<Frustum>& volumes);

}  // namespace hs::render
