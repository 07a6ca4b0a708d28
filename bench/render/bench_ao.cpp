// bench_ao: ambient occlusion (settings.ao: ssao, gtao) against a CPU ray
// cast of the same depth buffer (tests/common/ao_reference.h: a floor, two
// spheres, a wall, ambient light only), error against run time.
//
// For each method, AO resolution and radius: the mean and 95th-percentile
// absolute error of the visibility the renderer applied against the
// ray-cast visibility (cosine-weighted rays within the radius, through
// meshproc's BVH), its bias, and the ao pass's GPU time (fenced
// timestamps, median of --frames) at the image size; then the reference's
// own CPU time.
//
//   bench_ao [--frames N] [--size WxH] [--rays N]
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "tests/common/ao_reference.h"

using namespace hs;

namespace {

double aoPassMs(const render::FrameStats& st) {
  for (const render::PassStats& p : st.passes)
    if (p.name == "ao") return p.gpuMs;
  return -1.0;
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 3, width = 640, height = 480, rays = 256;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) frames = std::max(1, std::atoi(argv[++i]));
    else if (a == "--rays" && i + 1 < argc) rays = std::max(1, std::atoi(argv[++i]));
    else if (a == "--size" && i + 1 < argc && std::sscanf(argv[++i], "%dx%d", &width, &height) == 2) {
    } else {
      std::fprintf(stderr, "usage: bench_ao [--frames N] [--size WxH] [--rays N]\n");
      return 2;
    }
  }
  render::OffscreenRenderer r;
  std::string error;
  if (!r.initialize(error)) {
    std::fprintf(stderr, "bench_ao: %s\n", error.c_str());
    return 1;
  }
  const test::AoScene sc = test::aoScene(width, height);
  std::printf("bench_ao at %dx%d, %s; %zu triangles; load %s\n\n", width, height, r.glDescription().c_str(),
              sc.world.triangleCount(), bench::loadAverageLine().c_str());
  std::printf("| method | resolution | radius m | mean error | 95th pct error | bias | ao pass GPU ms | reference s |\n");
  std::printf("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  for (float radius : {0.5f, 1.0f, 2.0f}) {
    const test::RenderedAo depthOnly = test::renderAo(r, sc, scene::AmbientOcclusion::Ssao, radius);
    const double t0 = bench::nowSeconds();
    const std::vector<float> reference = test::rayCastAo(sc, depthOnly.depth, radius, rays);
    const double refSeconds = bench::nowSeconds() - t0;
    for (auto [ao, name] : {std::pair{scene::AmbientOcclusion::Ssao, "ssao"}, std::pair{scene::AmbientOcclusion::Gtao, "gtao"}})
      for (auto [res, resName] : {std::pair{scene::AoResolution::Full, "full"}, std::pair{scene::AoResolution::Half, "half"}}) {
        std::vector<double> ms;
        test::AoError e;
        for (int f = 0; f < frames; ++f) {
          const test::RenderedAo got = test::renderAo(r, sc, ao, radius, res);
          ms.push_back(aoPassMs(got.stats));
          if (f == 0) e = test::compareAo(got.visibility, reference);
        }
        std::printf("| %s | %s | %.1f | %.4f | %.4f | %+.4f | %.2f | %.1f |\n", name, resName, double(radius), e.mean,
                    e.p95, e.bias, bench::median(ms), refSeconds);
        std::fflush(stdout);
      }
  }
  std::printf("\n%d reference rays a pixel (a stratified cosine-weighted grid); load %s\n", rays,
              bench::loadAverageLine().c_str());
  return 0;
}
