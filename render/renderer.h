#pragma once
// The renderer: draws a SceneState from a RenderView into a framebuffer of
// whatever OpenGL 4.5 core context is current, the editor's QOpenGLWidget
// or a headless EGL context (egl_context.h). It calls GL through libepoxy
// and holds no window-system code.
//
// A frame is a graph of passes (frame_graph.h), built each frame for what
// the frame needs: a pass the frame does not need is not added or is culled,
// and its resources are never allocated (no MSAA targets unless MSAA is on,
// no FXAA pass unless FXAA is on, no terrain pass without terrains, no grid
// without a grid, no overlay pass without overlays). The scene's data for
// the GPU (matrices, lights, the visible set) is built once per frame and
// shared by every view of it: renderViews() draws both eyes of a stereo pair
// in one frame.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "foliage/impostor_images.h"
#include "render/overlay.h"
#include "render/render_view.h"
#include "render/terrain_lod.h"
#include "scene/scene_state.h"
#include "sequencer/camera_cuts.h"

namespace hs::render {

class DrawSource;  // render/draw_source.h (inside the renderer)

// One pass of the last frame (frame_graph.h): CPU time around its
// commands, GPU time between timestamps (with RenderOptions::passTimings),
// and the bytes of the transient resources it brought into use.
struct PassStats {
  std::string name;
  double cpuMs = 0.0;
  double gpuMs = -1.0;
  size_t gpuBytes = 0;
};

// What the renderer holds on the GPU, one entry per allocation: the frame
// graph's pooled and persistent textures and buffers, and the mesh and
// terrain caches. The source of truth for "a pass the frame does not need
// holds no memory" (tests read it) and for `render --stats`.
struct GpuAllocation {
  std::string name;
  std::string kind;  // "texture", "buffer", "meshes", "terrains"
  size_t bytes = 0;
  bool transient = false;  // from the frame graph's pool (not persistent)
  // Pooled memory serves several resources of a frame in turn: all of them,
  // `name` (the last) included.
  std::vector<std::string> users{};
};

// Transparency (render/oit.h) in one frame, summed over its views; all
// zero when no translucent surface was in view (then nothing was allocated).
struct OitStats {
  bool active = false;         // translucent surfaces were drawn
  std::string mode;            // settings.transparency's name
  size_t bytes = 0;            // GPU memory of the OIT buffers
  bool counted = false;        // fragments below are known (every mode but weighted/reference without a count)
  uint64_t fragments = 0;      // translucent fragments in front of the opaque surfaces
  uint32_t maxPerPixel = 0;    // the deepest pixel
  double meanPerPixel = 0.0;   // over pixels with at least one
  uint64_t coveredPixels = 0;
  uint64_t overflow = 0;       // fragments that found no place and were tail-blended
  double tailShare = 0.0;      // mean share of the tail in the pixels that have one (0..1)
  uint64_t tailPixels = 0;
  int layers = 0;              // abuffer_fixed: layers; kbuffer: K used (both shrink under the cap); abuffer: the per-pixel cap when the memory cap bites, else 0
  int peels = 0;               // reference: layers peeled
};

// Cluster hierarchies drawn this frame (render/cluster_source.h).
struct ClusterStats {
  size_t instances = 0;     // instances drawn from their hierarchy (the rest: their coarse mesh)
  size_t clusters = 0, triangles = 0;  // of their cuts (each camera view culls them further)
  size_t pagesResident = 0;  // on the GPU
  size_t pagesDrawn = 0;     // of which the cuts draw (what a budget must hold at least)
  size_t pagesWanted = 0;    // the cuts want and lack (0: every cut whole)
  size_t pagesLoading = 0;   // of which are on their way (not failed): a streaming view draws again for them
  size_t gpuBytes = 0, cpuBytes = 0;  // the GPU pool, the CPU page cache
  bool complete = true;      // every cut is the one the pixel bound asks for
  bool budgetFull = false;   // a wanted page found no slot: the GPU budget holds only this frame's pages
  double cutMs = 0.0;        // choosing the cuts and uploading pages (with waiting, when the frame waits)
};

struct FrameStats {
  size_t trianglesDrawn = 0;
  size_t drawCalls = 0;
  size_t instancesDrawn = 0;
  size_t particlesDrawn = 0;     // particles in the frame's buffer (render/particle_source.h), each view draws them
  size_t emittersOutOfView = 0;  // emitters skipped unevaluated: their bound (particles/bounds.h) is in no view (mesh particles: nor their shadow)
  size_t instancesCulled = 0;
  size_t instancesAtCoarserLod = 0;  // drawn with a mesh LOD level above 0 (mesh_lod.h)
  size_t terrainTriangles = 0;   // included in trianglesDrawn
  size_t terrainPatches = 0;     // CDLOD quadrants drawn
  size_t terrainUploadBytes = 0; // tile data uploaded this frame (a brush dab: its region)
  double terrainUploadMs = 0.0;  // CPU time of those uploads and the LOD bookkeeping
  double cpuMs = 0.0;
  double gpuMs = -1.0;     // from a timer query of an earlier frame; -1 until known
  size_t gpuBytes = 0;     // what the frame holds (resourceRegistry())
  // Pooled targets no pass of this frame used, kept a few frames for a
  // frame that asks again (a viewport switching mono and stereo): held on
  // the GPU too, not in gpuBytes.
  size_t idleGpuBytes = 0;
  // GL textures and buffers the pool has made since the renderer began:
  // flat while frames reuse what they had.
  size_t gpuAllocationsMade = 0;
  std::vector<PassStats> passes;  // the passes that ran, in order
  // Clustered lights (render/passes/light_culling.h): point and spot lights
  // whose range reaches a view; clusters reached by more lights than the
  // cap (128: the rest are left out there) and the most lights one cluster
  // had, known only when the frame has more lights than the cap.
  size_t lightsInView = 0;
  size_t lightClustersOverCap = 0;
  size_t lightsMaxPerCluster = 0;
  OitStats oit;
  ClusterStats clusters;
};

struct RenderOptions {
  bool showGrid = true;          // AND-ed with the scene setting
  const Overlay* overlay = nullptr;
  bool keepHdr = false;          // keep the linear HDR image for readHdr()
  bool measureGpuTime = false;   // timer queries (editor status bar)
  // Mesh LOD levels are chosen as seen from this view when set, not from the
  // one drawn: the two eyes of a stereo pair pass their camera's (mono)
  // view, so both draw the same level of every mesh (a level switching in
  // one eye only is a flicker the viewer sees as rivalry). Culling stays
  // per eye. Terrain LOD is still chosen per eye.
  const RenderView* lodView = nullptr;
  bool passTimings = false;      // GPU timestamps per pass; waits for them (stats, benchmarks)
  bool keepDepth = false;        // keep a single-sample depth for readDepth()
  // Emitters that collide with nothing evaluated by a compute pass (render/
  // particle_gpu_eval.h) instead of on the CPU; not culled per particle.
  bool gpuParticles = false;
  // Meshes write their shading normal (world axes, after normal and
  // parallax mapping) instead of a colour: read it with keepHdr/readHdr
  // (tests of the maps). Gouraud materials are not affected.
  bool debugShadingNormal = false;
  // Every pixel loops over every point and spot light of the frame instead
  // of its cluster's (tests and bench_lights compare the two).
  bool bruteForceLights = false;
  // Transparency: count fragments per pixel in every mode (the weighted
  // and reference modes need an extra pass for it; --stats asks), and
  // show the depth complexity of translucent surfaces as a heat map
  // instead of the scene (the viewport's view mode).
  bool oitCounts = false;
  bool depthComplexity = false;
  // The editor's before/after split (View > Post Before/After): in (0, 1),
  // the share of the width, from the left, that shows the frame without
  // its post effects (exposure, the tone map and sRGB only), with a line
  // at the border; 0 (or no effect on): the frame as it is.
  float postSplit = 0.0f;
  // Cluster hierarchies (render/cluster_source.h): the editor's viewport
  // draws what is resident and lets pages stream in over the next frames;
  // without it (exports, render nodes, tests) a frame waits until every
  // page its cut wants is in memory, so it is exact in any run.
  bool streamClusters = false;
  // Colour every cluster of a hierarchy by its level (the viewport's view
  // mode; shaders/cluster_level.frag) instead of its material.
  bool clusterLevels = false;
};

// One view of a frame and the framebuffer it ends in.
struct ViewTarget {
  RenderView view;
  unsigned fbo = 0;
  std::string name;  // names its passes ("left" -> "opaque[left]"); empty for one view
};

// What bringing a terrain's GPU copy up to date did (Renderer::syncTerrain).
struct TerrainUpload {
  size_t bytes = 0;
  size_t regions = 0;
  double cpuMs = 0.0;    // on the calling thread: the GL upload calls and the LOD bookkeeping
  double lodMs = 0.0;    // of which the CDLOD bounds and LOD errors
  bool full = false;
  double gpuMs = -1.0;   // with measureGpu: GL_TIME_ELAPSED around the uploads (waits for the result)
  double finishMs = -1.0;  // with measureGpu: glFinish after them (until the GPU has the data)
};

// What is under a pixel (Renderer::pickSurface): the entity and the view
// depth of its surface there (metres along the view axis; 0 where nothing is).
struct PickHit {
  scene::EntityId entity = scene::kNoEntity;
  double viewDepth = 0.0;
  uint32_t instance = UINT32_MAX;  // an instanced source's instance id (UINT32_MAX: the entity as a whole)
};

// One cascade of the sun's shadow maps in the last frame (tests, benchmarks):
// the view depth it serves, its texel size and the lookup matrix
// (frame-relative position -> map u, v, depth) with the frame origin.
struct SunCascadeInfo {
  double splitNear = 0.0, splitFar = 0.0;
  double texelMetres = 0.0;
  glm::dmat4 frameToMap{1.0};
  glm::dvec3 frameOrigin{0.0};
};

// A shader program the renderer has built: its files and the defines of
// its variant (tests of "a scene builds only the variants it needs").
struct BuiltProgram {
  std::string name;  // "mesh.vert + mesh.frag [FOG_HEIGHT]"
  std::vector<std::string> defines;
};

// One camera or stereo pair of a frame that holds several (a transition
// between two shots, Renderer::renderGroups): its targets, and the view
// that chooses its levels of detail (null: targets[0].view).
struct ViewGroup {
  std::vector<ViewTarget> targets;
  const RenderView* lodView = nullptr;
};

// How renderGroups combines its groups' images: view i of every group
// (linear HDR, before the exposure), weighted and summed, then tone mapped
// into targets[i] like a frame's own output (a cross-fade between two
// shots: weights 1 - a and a). With a patterned `transition`
// (sequencer::isPatterned) the first two groups (outgoing, incoming) are
// combined by its pattern at `progress` instead of the weights; `frame`
// seeds the patterns that change from frame to frame (glitch). Both eyes
// get the same pattern in screen space (docs/sequencer.md "Transitions").
struct GroupCombine {
  std::vector<ViewTarget> targets;  // one per view of a group; every group has as many
  std::vector<float> weights;       // one per group
  sequencer::Transition transition = sequencer::Transition::Crossfade;
  float progress = 0.0f;  // eased, in (0, 1)
  int64_t frame = 0;
};

// How a transition's `shot` at `frame` combines (its weights, kind and
// progress); the caller adds the targets.
inline GroupCombine combineOf(const sequencer::Shot& shot, int64_t frame) {
  const auto [outgoing, incoming] = shot.weights();
  return GroupCombine{{}, {outgoing, incoming}, shot.transition, float(shot.progress), frame};
}

class Renderer {
 public:
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Needs a current GL 4.5 core context. False with `error` if the context
  // lacks what the renderer needs or a shader fails to build.
  bool initialize(std::string& error);
  bool initialized() const;
  // Fills framebuffer `fbo` with one colour, on any current context, also
  // one initialize() refused (the viewport's background when the scene
  // cannot be drawn): only calls every GL 3.0 context has.
  static void clearTarget(unsigned fbo, float r, float g, float b);

  // Renders into framebuffer `targetFbo` (0 = default) of size view.width x
  // view.height, leaving it holding sRGB-encoded 8-bit colour.
  FrameStats render(const scene::SceneState& state, const RenderView& view, unsigned targetFbo,
                    const RenderOptions& options = {});
  // Several views of one frame (the eyes of a stereo pair): the frame's data
  // and visible set are built once; levels of detail come from
  // options.lodView (views[0] when it is null). Stats are the frame's.
  FrameStats renderViews(const scene::SceneState& state, const std::vector<ViewTarget>& views,
                         const RenderOptions& options = {});
  // Several view groups in one frame: each group has its own visible set,
  // levels of detail, shadow maps and light grid, rendered by a frame
  // graph of its own in turn (they share the pool, the mesh and terrain
  // caches and the environment), into its own targets, exactly as
  // renderViews would render it alone. With `combine`, their HDR images
  // are then combined into combine->targets (a last graph). readHdr and
  // readDepth number the views of all groups in order, then (with keepHdr)
  // the combined images. One group costs
  // what renderViews costs. GPU time is not measured (per-pass timings are).
  std::vector<FrameStats> renderGroups(const scene::SceneState& state, const std::vector<ViewGroup>& groups,
                                       const RenderOptions& options = {}, const GroupCombine* combine = nullptr);

  // Reads back what the last render() wrote to `targetFbo`.
  Image readDisplay(unsigned targetFbo, int width, int height) const;
  // Linear HDR of view `view` of the last frame rendered with keepHdr: the
  // scene's light in scene units (scene/light_units.h), before the exposure
  // and the tone map, which the tone map pass applies.
  Image readHdr(size_t view = 0) const;
  // The same into `dst`, or, with a GL_PIXEL_PACK_BUFFER bound, at offset
  // `dst` in it without waiting (the export's asynchronous readback).
  // RGBA32F, bottom row first.
  void readHdrInto(void* dst, size_t bytes, size_t view = 0) const;
  // Reversed-Z depth of view `view` of the last frame rendered with
  // keepDepth (32-bit float: 1 at the near plane, 0 at the far plane and
  // where nothing was drawn), bottom row first, into `dst` or the bound pixel
  // pack buffer, for the stereo comfort check.
  void readDepth(void* dst, size_t view = 0);

  // What the renderer holds on the GPU for the last frame (see
  // GpuAllocation): its pooled targets and everything persistent. Pooled
  // targets that frame did not use, kept for reuse, are counted apart
  // (FrameStats::idleGpuBytes, idlePoolBytes).
  std::vector<GpuAllocation> resourceRegistry() const;
  size_t idlePoolBytes() const;

  // The entity under window pixel (x, y) (origin top-left), or 0. Renders an
  // id pass for that pixel only.
  scene::EntityId pick(const scene::SceneState& state, const RenderView& view, int x, int y);
  // The same id pass with the surface's depth there (focus picking).
  PickHit pickSurface(const scene::SceneState& state, const RenderView& view, int x, int y);

  // Kinds of geometry drawn after the document's meshes and terrains
  // (render/draw_source.h, inside the renderer): tests and benchmarks add
  // their own. The document's foliage and particles are drawn without this
  // (foliage_sources.h, particle_source.h).
  void setDrawSources(std::vector<std::shared_ptr<DrawSource>> sources);

  // Emitters the last frame left out, each naming the emitter and the
  // field ("emitter 'Debris', field 'draw_mesh': no entity 'Rock' with a
  // mesh"); the rest of the frame drew (render/particle_source.h).
  std::vector<std::string> particleErrors() const;

  // Frees GPU copies of assets that left the scene.
  void collectGarbage(const scene::SceneState& state);

  // Bakes the octahedral impostor of mesh asset `asset` as a frame would
  // (its level 0 with its document materials, render/impostor_cache.h) and
  // reads it back for the scene to store (scene/impostor_ops.h); the atlas
  // stays on the GPU for the next frames. Nullopt with `error` for an asset
  // that is not there or has no drawable mesh. Call between frames.
  std::optional<foliage::ImpostorImages> bakeImpostor(const scene::SceneState& state, scene::AssetId asset,
                                                      std::string& error);
  // Impostor atlases baked here and uploaded from stored images so far.
  size_t impostorsBaked() const;
  size_t impostorsUploaded() const;

  // Terrains (terrain_pass.h). Uploads what changed in `data` since the GPU
  // copy was last synced, without drawing (render() does this itself; the
  // benchmarks time it alone).
  TerrainUpload syncTerrain(const scene::TerrainData& data, bool measureGpu = false);
  // The CDLOD selection render() would draw for a terrain entity (tests,
  // benchmarks, the editor's statistics).
  LodSelection terrainLod(const scene::SceneState& state, scene::EntityId entity, const RenderView& view);
  // Terrain material textures that could not be read, as found since the
  // last call (each names the terrain, material and file; terrain_pass.h).
  std::vector<std::string> takeTerrainMaterialProblems();
  // OpenGL debug output since the last call (gl/gl_debug.h: debug builds,
  // or HS_GL_DEBUG set), one line each.
  std::vector<std::string> takeGlMessages();
  // Material textures that could not be drawn (missing, empty, larger than
  // the GPU allows, damaged, a grey normal map), each named by material and
  // field and reported once; the frame draws without them (material_table.h).
  std::vector<std::string> takeMaterialProblems();

  // Shadow settings that had to be clamped (a resolution of 0, or larger
  // than the GPU allows), each naming the field, reported once; the frame
  // renders with the clamped value.
  std::vector<std::string> takeShadowProblems();
  // Light clusters over the cap (render/passes/light_culling.h), reported
  // once when they start; the frame renders without the extra lights there.
  std::vector<std::string> takeLightProblems();
  // Camera lenses that depth of field refused (an f-stop or focus distance
  // that is not a positive number), each naming the camera and the field,
  // reported once; the frame renders without depth of field.
  std::vector<std::string> takeDofProblems();
  // A grading LUT left out of the frame (its tables or its program could
  // not be made), naming the file, reported once until the problem changes.
  std::vector<std::string> takeLutProblems();
  // Cluster pages that could not be read (damaged or missing), each naming
  // the file, the asset and the page, reported once; the coarser level is
  // drawn there.
  std::vector<std::string> takeClusterProblems();
  // Every program built since initialize(), initialisation's included.
  std::vector<BuiltProgram> builtPrograms() const;
  // The sun's cascades of the last frame (empty: no sun shadow).
  std::vector<SunCascadeInfo> sunCascades() const;

  // Frees every GL object (call with the context current, before it goes).
  void shutdown();

 private:
  // The frame's memory figures (gpuBytes, idleGpuBytes, gpuAllocationsMade).
  void fillMemoryStats(FrameStats& stats) const;
  // settings.depth_of_field = reference (render/dof_reference.h); nullopt
  // when no view needs depth of field (the frame then renders as usual).
  std::optional<FrameStats> renderLensReference(const scene::SceneState& state, const std::vector<ViewTarget>& views,
                                                const RenderOptions& options);

  struct Impl;
  std::unique_ptr<Impl> d_;
};

// Which GL the current context is: "llvmpipe (LLVM 15) | 4.5 (Core Profile) Mesa 22.3.6".
std::string currentGlDescription();

}  // namespace hs::render
