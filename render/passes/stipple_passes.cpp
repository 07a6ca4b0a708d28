#include "render/passes/stipple_passes.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "render/passes/fullscreen_pass.h"
#include "render/stereo_views.h"

namespace hs::render {

namespace {

constexpr uint32_t kNoOwner = 0xffffffffu;

// The second eye of a stereo pair: the first eye's final dots and depth,
// this eye's depth, and the map from the first eye's window coordinates
// (x, y in NDC, z its depth) to this eye's clip space.
struct Reprojection {
  BufferRef sites;
  TextureRef firstDepth, depth;
  glm::mat4 firstToThis{1.0f};
};

// The relaxation: one pass of many dispatches (shaders/stipple.comp), its
// buffers its own; the sites map of the final cells out, and the sites
// (their final positions) in `sitesOut`. With `from`, the first slots hold
// the first eye's dots reprojected (fixed), the next ones this eye's own
// candidates where none of those lands near.
TextureRef addRelaxation(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef density,
                         const StippleLayout& layout, int iterations, const Reprojection* from, BufferRef* sitesOut) {
  struct Data {
    TextureRef density, map, firstDepth, depth;
    BufferRef sites, seeds, ownerA, ownerB, sums, firstSites;
  };
  const int gw = layout.gridWidth, gh = layout.gridHeight;
  const size_t cells = size_t(gw) * size_t(gh);
  const uint32_t fixed = from ? layout.candidates : 0u;  // the reprojected dots' slots
  const uint32_t total = fixed + layout.candidates;
  // Hole filling needs a flood before the steps, and its sums buffer none.
  const bool floods = iterations > 0 || from;
  Data out;
  TextureRef map = graph
      .addPass<Data>(
          v.named("stipple_relax"),
          [&](PassBuilder& b, Data& d) {
            d.density = b.read(density);
            d.map = b.create(v.named("stipple_sites_map"), TextureDesc{gw, gh, GL_RG32F}, Usage::Storage);
            d.sites = b.create(v.named("stipple_sites"), BufferDesc{size_t(total) * 8});
            d.ownerA = b.create(v.named("stipple_owner_a"), BufferDesc{cells * 4});
            d.ownerB = b.create(v.named("stipple_owner_b"), BufferDesc{cells * 4});
            // The Lloyd steps' buffers: none without a step.
            if (floods) d.seeds = b.create(v.named("stipple_seeds"), BufferDesc{cells * 4});
            if (iterations > 0) d.sums = b.create(v.named("stipple_sums"), BufferDesc{size_t(total) * 20});
            if (from) {
              d.firstSites = b.read(from->sites);
              d.firstDepth = b.read(from->firstDepth);
              d.depth = b.read(from->depth);
            }
            out = d;
          },
          [&frame, layout, iterations, fixed, total, floods, toThis = from ? from->firstToThis : glm::mat4(1.0f),
           scale = glm::vec2(float(v.view.width) / float(gw), float(v.view.height) / float(gh))](
              const Data& d, const PassResources& r) {
            const glm::ivec2 size(layout.gridWidth, layout.gridHeight);
            const GLuint gx = GLuint(size.x + 7) / 8u, gy = GLuint(size.y + 7) / 8u;
            // A stage over `count` slots from `first` (per-cell stages ignore them).
            auto stage = [&](const char* define, uint32_t count = 0, uint32_t first = 0) -> GlProgram& {
              GlProgram& p = frame.res.program({"", "", "stipple.comp", {define}});
              p.set("uSize", size);
              p.set("uCount", count);
              p.set("uFirst", first);
              p.use();
              return p;
            };
            auto groups = [](uint32_t count) { return GLuint((count + 63u) / 64u); };
            auto barrier = [] { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT); };
            glBindTextureUnit(0, r.texture(d.density));
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, r.buffer(d.sites));
            if (iterations > 0) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, r.buffer(d.sums));
            if (fixed > 0) {
              // The first eye's dots where this eye sees them.
              glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, r.buffer(d.firstSites));
              glBindTextureUnit(1, r.texture(d.firstDepth));
              glBindTextureUnit(2, r.texture(d.depth));
              GlProgram& p = stage("HS_STIPPLE_REPROJECT", fixed);
              p.set("uFirstToThis", toThis);
              p.set("uPixelsPerCell", scale);
              glDispatchCompute(groups(fixed), 1, 1);
            }
            stage("HS_STIPPLE_SEED", layout.candidates, fixed);
            glDispatchCompute(groups(layout.candidates), 1, 1);
            barrier();
            // owners[0]: the cells being flooded (at the end, the final
            // ones); owners[1]: the other half of the ping-pong; seeds: the
            // splat of the sites where they are now.
            GLuint owners[2] = {r.buffer(d.ownerA), r.buffer(d.ownerB)};
            const GLuint seeds = floods ? r.buffer(d.seeds) : 0;  // used from the second flood on
            int first = 1;
            while (first * 2 < std::max(size.x, size.y)) first *= 2;
            // The first flood: jump flooding from the seeds, steps from half
            // the grid's extent down to 1, and 1 again (JFA+1: most of the
            // plain scheme's errors go). After a Lloyd step the cells move
            // by about as much as the sites did, under a spacing: the flood
            // starts from the nearer of each cell's seed and its owner
            // before, with steps from the spacing's power of two down.
            int shortFirst = 1;
            while (float(shortFirst) < layout.spacingCells) shortFirst *= 2;
            bool flooded = false;
            auto flood = [&](uint32_t count) {
              // The seeds: into the flood's buffer the first time, beside the
              // cells before (then merged with them in place) after.
              const GLuint target = flooded ? seeds : owners[0];
              glClearNamedBufferData(target, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &kNoOwner);
              glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, target);
              stage("HS_STIPPLE_SPLAT", count);
              glDispatchCompute(groups(count), 1, 1);
              barrier();
              if (flooded) {
                glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, owners[0]);
                stage("HS_STIPPLE_MERGE");
                glDispatchCompute(gx, gy, 1);
                barrier();
              }
              std::vector<int> steps;
              for (int k = flooded ? std::min(shortFirst, first) : first; k >= 1; k /= 2) steps.push_back(k);
              steps.push_back(1);
              GlProgram& jump = stage("HS_STIPPLE_JUMP");
              for (int k : steps) {
                jump.set("uStep", k);
                glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, owners[0]);
                glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, owners[1]);
                glDispatchCompute(gx, gy, 1);
                barrier();
                std::swap(owners[0], owners[1]);
              }
              glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, owners[0]);  // the final cells
              flooded = true;
            };
            if (fixed > 0) {
              // This eye's own candidates only where no reprojected dot is
              // near (by the spacing the darkness there asks for), then a
              // whole flood again: the holes can be wider than a short one
              // reaches.
              flood(fixed);
              GlProgram& fill = stage("HS_STIPPLE_FILL", layout.candidates, fixed);
              fill.set("uSpacing", layout.spacingCells);
              glDispatchCompute(groups(layout.candidates), 1, 1);
              barrier();
              flooded = false;
            }
            for (int i = 0; i < iterations; ++i) {
              flood(total);
              const uint32_t zero = 0;
              glClearNamedBufferData(r.buffer(d.sums), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
              stage("HS_STIPPLE_SUM");
              glDispatchCompute(gx, gy, 1);
              barrier();
              stage("HS_STIPPLE_MOVE", total, fixed);  // the reprojected dots stay
              glDispatchCompute(groups(total), 1, 1);
              barrier();
            }
            flood(total);
            glBindImageTexture(0, r.texture(d.map), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
            stage("HS_STIPPLE_RESOLVE");
            glDispatchCompute(gx, gy, 1);
            glBindTextureUnit(0, 0);
            if (fixed > 0) {
              glBindTextureUnit(1, 0);
              glBindTextureUnit(2, 0);
            }
          })
      .map;
  if (sitesOut) *sitesOut = out.sites;
  return map;
}

}  // namespace

TextureRef addStipplePasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef ldr,
                            bool toTarget, TextureRef depth) {
  const scene::PostSettings& post = frame.settings.post;
  const int w = v.view.width, h = v.view.height;
  const StippleLayout layout = stippleLayout(post.stippleSpacingPx, post.stippleDotPx, w, h);

  FullscreenPass density;
  density.name = v.named("stipple_density");
  density.fragment = "stipple_density.frag";
  density.inputs = {{0, ldr}};
  density.outputName = v.named("stipple_density");
  density.output = TextureDesc{layout.gridWidth, layout.gridHeight, GL_R8};
  const TextureRef darkness = addFullscreenPass(graph, frame, v, std::move(density));
  // A stereo pair: the first view keeps its dots for the second.
  const int eye = stereoEye(frame, v, depth);
  Reprojection from;
  const FrameContext::FirstEye& first = frame.firstEye;
  const bool second = eye == 1 && first.stippleSites.valid() && first.stippleCount == layout.candidates;
  if (second) from = Reprojection{first.stippleSites, first.depth, depth, windowToClip(*first.view, v.view)};
  BufferRef sites;
  const TextureRef map = addRelaxation(graph, frame, v, darkness, layout, std::clamp(post.stippleIterations, 0, 50),
                                       second ? &from : nullptr, &sites);
  if (eye == 0) {
    frame.firstEye.stippleSites = sites;
    frame.firstEye.stippleCount = layout.candidates;
  }

  FullscreenPass dots;
  dots.name = v.named("stipple");
  dots.fragment = "stipple.frag";
  dots.inputs = {{0, map}};
  const glm::vec2 scale(float(w) / float(layout.gridWidth), float(h) / float(layout.gridHeight));
  // A site within reach of a pixel's ink (radius + 0.5) stands in a cell at
  // most this many cells from the pixel's each way, and owns that cell.
  const int reach = int(std::ceil((layout.radiusPx + 0.5f) / std::min(scale.x, scale.y)));
  dots.uniforms = [scale, radius = layout.radiusPx, reach](GlProgram& p) {
    p.set("uScale", scale);
    p.set("uRadius", radius);
    p.set("uReach", reach);
  };
  if (toTarget) {
    dots.toTarget = true;
  } else {
    dots.outputName = v.named("stippled_color");
    dots.output = TextureDesc{w, h, GL_RGBA8};
  }
  return addFullscreenPass(graph, frame, v, std::move(dots));
}

}  // namespace hs::render
