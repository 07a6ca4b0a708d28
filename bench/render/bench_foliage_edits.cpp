// bench_foliage_edits: what a brush edit of the document's foliage costs
// the renderer (render/foliage_sources.h), against rebuilding the sets the
// way every edit did before. A store of --counts instances (rocks, 2 m
// apart on a jittered grid, in the store's 64 m cells) is drawn through
// FoliageSources; then an erase dab and a paint dab (radius --radius m, in
// the field's middle) and a paint dab on bare ground beside the field (new
// cells), each followed by:
//   per cell   the kept sources' update: the touched cells packed again in
//              their slots, new cells given slots from a set's spare tail,
//              only those slots uploaded (the renderer's way)
//   rebuild    sources built afresh from the store and uploaded whole
//              (the way before per-cell slots; also what a cell grown past
//              its room costs)
// Columns: the update's CPU time (packing), the bytes the next frame
// uploaded, that frame's wall time (the view looks away from the field,
// so culling and the upload dominate, not drawing), and the ratio of
// bytes rebuild / per cell.
//
//   bench_foliage_edits [--counts 100000,1000000] [--radius 20]
#include <QCoreApplication>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "foliage/tools.h"
#include "mesh/primitives.h"
#include "render/foliage_sources.h"
#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "scene/foliage_data.h"
#include "scene/foliage_ground.h"
#include "scene/scene_state.h"
#include "tests/common/scene_parts.h"
#include "tests/common/view_from.h"

using namespace hs;

namespace {

constexpr scene::AssetId kGround = 1, kRock = 2;
constexpr double kSpacing = 2.0;

struct Row {
  double updateMs = 0.0, frameMs = 0.0;
  size_t bytes = 0;
};

}  // namespace

int main(int argc, char** argv) {
  QCoreApplication app(argc, argv);
  std::vector<double> counts = {1e5, 1e6};
  double radius = 20.0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--counts") counts = bench::numberList(argv[i + 1]);
    else if (a == "--radius") radius = std::stod(argv[i + 1]);
  }
  render::OffscreenRenderer r;
  std::string error;
  if (!r.initialize(error)) {
    std::fprintf(stderr, "bench_foliage_edits: %s\n", error.c_str());
    return 1;
  }
  std::printf("# bench_foliage_edits: a brush dab (radius %.0f m) in a field of rocks, per-cell update against a "
              "rebuild\n%s\n%s\n\n",
              radius, r.glDescription().c_str(), bench::loadAverageLine().c_str());
  std::printf("| instances | edit | way | update CPU ms | bytes uploaded | frame ms | bytes rebuild / per cell |\n");
  std::printf("|---:|---|---|---:|---:|---:|---:|\n");
  for (double c : counts) {
    const size_t n = size_t(c);
    scene::SceneState s;
    s.settings.showGrid = false;
    test::addMeshAsset(s, kRock, "Rock", mesh::uvSphere(0.5f, 8, 6), {0.6f, 0.55f, 0.5f});
    const size_t side = size_t(std::ceil(std::sqrt(double(n))));
    const double half = 0.5 * double(side) * kSpacing;
    // The ground the paint dab places on: a plane under the field.
    test::addMeshAsset(s, kGround, "Ground", mesh::gridPlane(float(2.0 * half + 300.0), 4), {0.5f, 0.5f, 0.45f});
    test::addMeshEntity(s, 1, "Ground", kGround, glm::dvec3(0.0));
    foliage::FoliageStore& store = scene::foliageOf(s).store();
    foliage::FoliageType t;
    t.name = "Rocks";
    t.mesh = "Rock";
    t.densityPerHa = 2500.0;
    t.spacing = 0.5;
    std::vector<std::string> messages;
    store.addType(t, messages);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-0.4 * kSpacing, 0.4 * kSpacing);
    for (size_t i = 0; i < n; ++i) {
      foliage::Instance in;
      in.position = glm::dvec3((double(i % side) + 0.5) * kSpacing - half + jitter(rng),
                               (double(i / side) + 0.5) * kSpacing - half + jitter(rng), 0.0);
      store.add(in, nullptr);
    }
    s.foliage->touch();
    scene::SceneState bare = s;  // the sources are drawn as given, not through the renderer's own
    bare.foliage.reset();
    // Looking up, away from the field: the frame is culling and uploads.
    const render::RenderView view = test::viewFrom({0.0, -half - 50.0, 20.0}, {0.0, -half - 60.0, 100.0}, 640, 360, 50.0);
    auto frame = [&](const std::vector<std::shared_ptr<render::InstancedSource>>& sources, size_t& bytes) {
      r.renderer().setDrawSources({sources.begin(), sources.end()});
      const double t0 = bench::nowSeconds();
      r.renderOnly(bare, view);
      const double ms = (bench::nowSeconds() - t0) * 1e3;
      r.renderer().setDrawSources({});
      bytes = 0;
      for (const auto& src : sources) bytes += src->lastUploadBytes();
      return ms;
    };
    render::FoliageSources kept;
    size_t bytes = 0;
    frame(kept.update(s), bytes);  // the first build and upload
    const scene::FoliageGround ground(s);
    for (const char* edit : {"erase", "paint", "paint on bare ground"}) {
      // Bare ground: past the field's edge by more than the dab, in cells
      // the store does not have.
      const glm::dvec2 at = std::string(edit) == "paint on bare ground" ? glm::dvec2(half + 100.0, 3.0) : glm::dvec2(7.0, 3.0);
      size_t touched = 0;
      if (std::string(edit) == "erase") {
        touched = foliage::erase(store, foliage::Region2::disc(at, radius)).undo.cellCount();
      } else {
        foliage::PaintParams p;
        p.region = foliage::Region2::disc(at, radius);
        p.types = {0};
        touched = foliage::paint(store, ground.ground(), p).undo.cellCount();
      }
      s.foliage->touch();
      Row per, full;
      double t0 = bench::nowSeconds();
      const auto& sources = kept.update(s);
      per.updateMs = (bench::nowSeconds() - t0) * 1e3;
      per.frameMs = frame(sources, per.bytes);
      render::FoliageSources fresh;
      t0 = bench::nowSeconds();
      const auto& rebuilt = fresh.update(s);
      full.updateMs = (bench::nowSeconds() - t0) * 1e3;
      full.frameMs = frame(rebuilt, full.bytes);
      const std::string ratio = per.bytes ? std::to_string(int(double(full.bytes) / double(per.bytes) + 0.5)) + "x" : "-";
      std::printf("| %zu | %s, %zu cell(s) | per cell%s | %.2f | %zu | %.1f | %s |\n", n, edit, touched,
                  kept.lastRebuilt() ? " (rebuilt)" : "", per.updateMs, per.bytes, per.frameMs,
                  ratio.c_str());
      std::printf("| %zu | %s | rebuild | %.2f | %zu | %.1f | |\n", n, edit, full.updateMs, full.bytes, full.frameMs);
      std::fflush(stdout);
    }
  }
  return 0;
}
