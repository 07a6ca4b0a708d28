#pragma once
// What the renderer keeps from frame to frame on the GPU, shared by its
// passes: the shader library, the transient-resource pool (and registry),
// the mesh and terrain caches, and the buffers every frame fills (frame and
// view uniforms, lights, object data). Include only inside render/.
#include <cstddef>
#include <string>
#include <vector>

#include "render/frame_blocks.h"
#include "render/gl/gl_handle.h"
#include "render/gl/shader_library.h"
#include "render/color_lut.h"
#include "render/environment_maps.h"
#include "render/gpu_mesh_cache.h"
#include "render/impostor_cache.h"
#include "render/material_table.h"
#include "render/resource_pool.h"
#include "render/local_shadows.h"
#include "render/shadow_cascades.h"
#include "render/terrain_pass.h"

namespace hs::render {

// A buffer that grows to what a frame needs and keeps its size.
struct GrowingBuffer {
  gl::Buffer buffer;
  size_t capacity = 0;
  // Makes room for `bytes` (at least `minimum`); true if the buffer is new.
  bool reserve(size_t bytes, size_t minimum = 4096);
  void upload(const void* data, size_t bytes, size_t offset = 0);
};

// Shadows (render/passes/shadow_passes.h): what outlives a frame. The maps
// and caster data are the frame graph's (transient, only when a light casts).
struct ShadowResources {
  GrowingBuffer block;   // ShadowBlock, bound at kShadowBlockBinding every frame (cascade count 0: none)
  SunCascades sun;       // the last frame's sun cascades (empty: none)
  std::vector<LocalShadow> local;  // the last frame's spot and point light maps (local_shadows.h)
  std::string localProblem;        // the last lights' problem reported
  std::string problem;   // the last settings problem reported (each is reported once)
  std::vector<std::string> newProblems;
};

struct RenderResources {
  gl::ShaderLibrary shaders;
  ResourcePool pool;
  GpuMeshCache meshes;
  ImpostorCache impostors;      // instanced types' far level (instanced_source.h), baked on first need
  MaterialTable materials;      // the frame's materials and standalone textures
  GrowingBuffer materialBlock;  // GpuMaterial[] at kMaterialBufferBinding
  TerrainPass terrain;  // runs only for scenes with a visible terrain
  ShadowResources shadows;

  GrowingBuffer frameBlock;     // FrameBlock
  GrowingBuffer viewBlocks;     // one ViewBlock per view, at viewStride
  size_t viewStride = 256;      // GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT rounded up
  GrowingBuffer lights;         // GpuLight[]
  GrowingBuffer fogBlock;       // FogBlock (fog_block.h), allocated by the first frame with fog
  GrowingBuffer objects;        // GpuObject[]
  GrowingBuffer objectIndices;  // uint 0..N-1: the per-instance attribute 7 of mesh VAOs
  size_t objectIndexCount = 0;

  gl::VertexArray emptyVao;     // full-screen triangles, generated quads
  gl::VertexArray overlayVao;
  GrowingBuffer overlayVertices;

  EnvironmentMaps environment;  // the analytic sky's image-based light (none with the gradient sky)
  GpuLutCache luts;             // the grading LUT's tables (none without a LUT)
  GpuLutCache viewTransforms;   // the OpenColorIO view transform's tables (none without one)
  // A LUT or view transform left out: reported once (lutProblems,
  // Renderer::takeLutProblems) until the problem changes; a program that
  // did not build is not built again for the same transform every frame.
  std::string lastLutProblem, lastViewProblem;
  std::vector<std::string> lutProblems;
  uint64_t lutProgramRefused = 0;
  std::string lutProgramError;
  std::string viewProgramRefused;  // config hash, display and view
  std::string viewProgramError;

  // Clustered lights (passes/light_culling.h): clusters over the cap are
  // reported once until a frame has none again.
  std::vector<std::string> lightProblems;
  bool lightOverflowReported = false;

  // Depth of field (passes/dof_passes.h): refused lenses not yet taken,
  // and the last one reported (each reported once until it changes).
  std::vector<std::string> dofProblems;
  std::string lastDofProblem;

  // The program of `desc` (all are built at initialisation, so this never
  // fails at draw time; it returns nullptr only for a desc that was not).
  GlProgram& program(const gl::ProgramDesc& desc);

  // Makes sure object indices 0..count-1 exist for the mesh VAOs.
  void ensureObjectIndices(size_t count);
  // Binds view `index`'s block at its binding point.
  void bindView(size_t index) const;
  void bindFrame() const;
};

}  // namespace hs::render
