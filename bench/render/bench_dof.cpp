// bench_dof: depth of field (settings.depth_of_field) against the
// lens-averaged reference the renderer computes (N pinhole frames over the
// aperture), error against run time: `layered` with K = 2, 4, 8 layers and
// `gather`, on tests/common/dof_scene.h's thin pole before an in-focus
// checkerboard wall (the partial-occlusion case) and its focus-point scene
// (a small square in focus, the wall blurred behind it).
//
// Per mode: the DoF passes' GPU time (fenced timestamps: the passes named
// dof_*, the A-buffer's counting and capture included; median of
// --frames), the whole frame's wall time (median), and RMSE, PSNR and the
// largest error of the 8-bit image against the reference, over the whole
// image and over the band around the pole. Writes a table and an
// error-against-time plot (--plot PATH).
//
//   bench_dof [--frames N] [--size WxH] [--samples N] [--plot PATH]
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "bench/common/plot.h"
#include "render/dof_lens.h"
#include "render/offscreen_renderer.h"
#include "tests/common/dof_scene.h"

using namespace hs;

namespace {

double dofPassMs(const render::FrameStats& st) {
  double ms = 0.0;
  for (const render::PassStats& p : st.passes)
    if (p.name.rfind("dof", 0) == 0 && p.gpuMs > 0) ms += p.gpuMs;
  return ms;
}

struct Mode {
  std::string name;
  scene::DepthOfField mode;
  int layers = 4;
};

}  // namespace

int main(int argc, char** argv) {
  int frames = 3, width = 640, height = 480, samples = 256;
  std::string plotPath = "bench_dof.png";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) frames = std::max(1, std::atoi(argv[++i]));
    else if (a == "--samples" && i + 1 < argc) samples = std::clamp(std::atoi(argv[++i]), 64, 1024);
    else if (a == "--plot" && i + 1 < argc) plotPath = argv[++i];
    else if (a == "--size" && i + 1 < argc && std::sscanf(argv[++i], "%dx%d", &width, &height) == 2) {
    } else {
      std::fprintf(stderr, "usage: bench_dof [--frames N] [--size WxH] [--samples N] [--plot PATH]\n");
      return 2;
    }
  }
  render::OffscreenRenderer r;
  std::string error;
  if (!r.initialize(error)) {
    std::fprintf(stderr, "bench_dof: %s\n", error.c_str());
    return 1;
  }
  std::printf("bench_dof at %dx%d, %s; reference: %d lens samples; load %s\n\n", width, height,
              r.glDescription().c_str(), samples, bench::loadAverageLine().c_str());
  const std::vector<Mode> modes = {{"gather", scene::DepthOfField::Gather},
                                   {"layered K=2", scene::DepthOfField::Layered, 2},
                                   {"layered K=4", scene::DepthOfField::Layered, 4},
                                   {"layered K=8", scene::DepthOfField::Layered, 8}};
  std::vector<bench::PlotPanel> panels;
  for (int which = 0; which < 2; ++which) {
    test::DofScene sc = which == 0 ? test::partialOcclusionScene() : test::focusPointScene();
    const char* sceneName = which == 0 ? "thin pole before a checkerboard (focus on the wall)"
                                       : "focus point before a blurred checkerboard";
    const render::RenderView view = sc.view(width, height);
    const render::DofLens lens = render::dofLensOf(view);
    // The band around the pole: its outline widened by the CoC radius.
    std::vector<bool> band(size_t(width) * size_t(height), false);
    glm::dvec2 left, right;
    const bool pole = which == 0 && view.project({-0.015, 2, 0}, left) && view.project({0.015, 2, 0}, right);
    const double radius = 0.5 * std::abs(lens.cocPixels(2.0));
    for (int y = 0; y < height && pole; ++y)
      for (int x = 0; x < width; ++x)
        band[size_t(y) * size_t(width) + size_t(x)] = x + 0.5 > left.x - radius - 2 && x + 0.5 < right.x + radius + 2;

    sc.state.settings.depthOfField = scene::DepthOfField::Reference;
    sc.state.settings.dofReferenceSamples = samples;
    double t0 = bench::nowSeconds();
    const Image reference = r.render(sc.state, view);
    const double referenceSeconds = bench::nowSeconds() - t0;
    sc.state.settings.depthOfField = scene::DepthOfField::Off;
    const Image pinhole = r.render(sc.state, view);

    const double near = which == 0 ? 2.0 : 12.0;  // the pole; the wall behind the focus point
    std::printf("### %s\n\nCoC diameter at %.0f m %.1f px, of the sky %.1f px; reference %.1f s\n\n", sceneName, near,
                std::abs(lens.cocPixels(near)), std::abs(lens.cocPixels(1e30)), referenceSeconds);
    std::printf("| mode | DoF passes GPU ms | frame ms | RMSE | PSNR dB | max | band RMSE | band PSNR dB | band max |\n");
    std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    bench::PlotPanel panel;
    panel.title = sceneName;
    panel.xLabel = "DoF passes, GPU ms";
    panel.yLabel = which == 0 ? "RMSE in the band around the pole (8-bit)" : "RMSE over the image (8-bit)";
    bench::PlotSeries series{"post passes", {200, 60, 40}, bench::PlotMarker::Circle, false, {}, {}};
    const auto row = [&](const std::string& name, const Image& img, double passMs, double frameMs) {
      const test::ImageError all = test::compareImages(img, reference);
      const test::ImageError b = test::compareImages(img, reference, band);
      if (pole)
        std::printf("| %s | %.1f | %.1f | %.2f | %.1f | %.0f | %.2f | %.1f | %.0f |\n", name.c_str(), passMs, frameMs,
                    all.rmse, all.psnr, all.maxError, b.rmse, b.psnr, b.maxError);
      else
        std::printf("| %s | %.1f | %.1f | %.2f | %.1f | %.0f | | | |\n", name.c_str(), passMs, frameMs, all.rmse,
                    all.psnr, all.maxError);
      std::fflush(stdout);
      if (passMs > 0) {
        series.points.emplace_back(passMs, pole ? b.rmse : all.rmse);
        series.pointLabels.push_back(name);
      }
    };
    row("off (pinhole)", pinhole, 0.0, 0.0);
    for (const Mode& m : modes) {
      sc.state.settings.depthOfField = m.mode;
      sc.state.settings.dofLayers = m.layers;
      std::vector<double> passMs, frameMs;
      Image img;
      for (int f = 0; f < frames; ++f) {
        render::RenderOptions o;
        o.passTimings = true;
        render::FrameStats st;
        t0 = bench::nowSeconds();
        img = r.render(sc.state, view, false, &st, o);
        frameMs.push_back((bench::nowSeconds() - t0) * 1e3);
        passMs.push_back(dofPassMs(st));
      }
      row(m.name, img, bench::median(passMs), bench::median(frameMs));
    }
    std::printf("\n");
    panel.series.push_back(series);
    panels.push_back(panel);
  }
  if (const std::string e = bench::savePlotPng(panels, plotPath, 700, 500); !e.empty())
    std::fprintf(stderr, "bench_dof: plot: %s\n", e.c_str());
  else
    std::printf("plot: %s\n", plotPath.c_str());
  std::printf("load %s; CPU %.1f s\n", bench::loadAverageLine().c_str(), bench::cpuSeconds(RUSAGE_SELF));
  return 0;
}
