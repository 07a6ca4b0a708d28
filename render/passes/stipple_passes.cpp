#include "render/passes/stipple_passes.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "render/passes/fullscreen_pass.h"

namespace hs::render {

namespace {

constexpr uint32_t kNoOwner = 0xffffffffu;

// The relaxation: one pass of many dispatches (shaders/stipple.comp), its
// buffers its own; the sites map of the final cells out.
TextureRef addRelaxation(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef density,
                         const StippleLayout& layout, int iterations) {
  struct Data {
    TextureRef density, map;
    BufferRef sites, seeds, ownerA, ownerB, sums;
  };
  const int gw = layout.gridWidth, gh = layout.gridHeight;
  const size_t cells = size_t(gw) * size_t(gh);
  return graph
      .addPass<Data>(
          v.named("stipple_relax"),
          [&](PassBuilder& b, Data& d) {
            d.density = b.read(density);
            d.map = b.create(v.named("stipple_sites_map"), TextureDesc{gw, gh, GL_RG32F}, Usage::Storage);
            d.sites = b.create(v.named("stipple_sites"), BufferDesc{size_t(layout.candidates) * 8});
            d.ownerA = b.create(v.named("stipple_owner_a"), BufferDesc{cells * 4});
            d.ownerB = b.create(v.named("stipple_owner_b"), BufferDesc{cells * 4});
            // The Lloyd steps' buffers: none without a step.
            if (iterations > 0) {
              d.seeds = b.create(v.named("stipple_seeds"), BufferDesc{cells * 4});
              d.sums = b.create(v.named("stipple_sums"), BufferDesc{size_t(layout.candidates) * 20});
            }
          },
          [&frame, layout, iterations](const Data& d, const PassResources& r) {
            const glm::ivec2 size(layout.gridWidth, layout.gridHeight);
            const GLuint siteGroups = (layout.candidates + 63u) / 64u;
            const GLuint gx = GLuint(size.x + 7) / 8u, gy = GLuint(size.y + 7) / 8u;
            auto stage = [&](const char* define) -> GlProgram& {
              GlProgram& p = frame.res.program({"", "", "stipple.comp", {define}});
              p.set("uSize", size);
              p.set("uCount", layout.candidates);
              p.use();
              return p;
            };
            auto barrier = [] { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT); };
            glBindTextureUnit(0, r.texture(d.density));
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, r.buffer(d.sites));
            if (iterations > 0) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, r.buffer(d.sums));
            stage("HS_STIPPLE_SEED");
            glDispatchCompute(siteGroups, 1, 1);
            barrier();
            // owners[0]: the cells being flooded (at the end, the final
            // ones); owners[1]: the other half of the ping-pong; seeds: the
            // splat of the sites where they are now.
            GLuint owners[2] = {r.buffer(d.ownerA), r.buffer(d.ownerB)};
            const GLuint seeds = iterations > 0 ? r.buffer(d.seeds) : 0;  // used from the second flood on
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
            auto flood = [&] {
              // The seeds: into the flood's buffer the first time, beside the
              // cells before (then merged with them in place) after.
              const GLuint target = flooded ? seeds : owners[0];
              glClearNamedBufferData(target, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &kNoOwner);
              glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, target);
              stage("HS_STIPPLE_SPLAT");
              glDispatchCompute(siteGroups, 1, 1);
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
            for (int i = 0; i < iterations; ++i) {
              flood();
              const uint32_t zero = 0;
              glClearNamedBufferData(r.buffer(d.sums), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
              stage("HS_STIPPLE_SUM");
              glDispatchCompute(gx, gy, 1);
              barrier();
              stage("HS_STIPPLE_MOVE");
              glDispatchCompute(siteGroups, 1, 1);
              barrier();
            }
            flood();
            glBindImageTexture(0, r.texture(d.map), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
            stage("HS_STIPPLE_RESOLVE");
            glDispatchCompute(gx, gy, 1);
            glBindTextureUnit(0, 0);
          })
      .map;
}

}  // namespace

TextureRef addStipplePasses(FrameGraph& graph, FrameContext& frame, const ViewContext& v, TextureRef ldr,
                            bool toTarget) {
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
  const TextureRef map =
      addRelaxation(graph, frame, v, darkness, layout, std::clamp(post.stippleIterations, 0, 50));

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
