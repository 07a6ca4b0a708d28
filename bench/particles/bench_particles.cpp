// Particles: how fast, how accurate (docs/particles.md, bench/particles/README.md).
//  1. Evaluations per second: frames of 100k and 1M particles on the closed
//     form (1 and all threads), and replay steps per second.
//  2. Error against run time of explicit Euler, semi-implicit Euler, RK4 and
//     the exact update, dt in {1e-3, 1e-2, 1e-1, 1} s, drag k in {0, 1, 100,
//     1e4} per second, against the closed form at T = 2 s (table and plot).
//  3. The replay (turbulence; turbulence with bounces on hills): error
//     against a 1e-4 s reference, by replay step.
//  4. A cold frame at t = 500 s (frame 30,000 at 60 fps: no cache) against
//     a warm one (the frame before it in the cache).
// Options: --quick (fewer particles), --plot FILE.png, --sprites DIR (writes
// the generated sprite textures as PNG).
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "bench/common/bench_util.h"
#include "bench/common/plot.h"
#include "core/image_io.h"
#include "particles/evaluate.h"
#include "particles/motion.h"
#include "particles/presets.h"
#include "particles/sprites.h"

using namespace hs::particles;
using hs::bench::nowSeconds;
using glm::dvec3;

namespace {

double maxAbs(const dvec3& a) { return std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)}); }

// Seconds per call of fn, over at least `minSeconds` (and at least one call).
template <class Fn>
double timeIt(Fn&& fn, double minSeconds = 0.05) {
  int reps = 0;
  const double t0 = nowSeconds();
  double t1 = t0;
  do {
    fn();
    ++reps;
    t1 = nowSeconds();
  } while (t1 - t0 < minSeconds);
  return (t1 - t0) / reps;
}

EmitterDesc fountain(double live) {
  EmitterDesc e;
  e.name = "Fountain";
  e.lifetimeMin = 2.0, e.lifetimeMax = 4.0;
  e.rate = live / 3.0;
  e.maxLive = 100000000;
  e.speedMin = 3, e.speedMax = 6;
  e.spreadDeg = 30;
  e.drag = 0.4;
  e.wind = {1.5, -0.5, 0};
  e.shape = Shape::Disc;
  return e;
}

HeightFieldCollider hills() {
  return HeightFieldCollider([](double x, double y) { return -2.0 + 0.3 * std::sin(0.7 * x) * std::cos(0.5 * y) + 0.1 * x; });
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, spritesOnly = false;
  std::string plotPath = "particles_error_vs_time.png", spriteDir;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) quick = true;
    else if (std::strcmp(argv[i], "--plot") == 0 && i + 1 < argc) plotPath = argv[++i];
    else if (std::strcmp(argv[i], "--sprites") == 0 && i + 1 < argc) spriteDir = argv[++i];
    else if (std::strcmp(argv[i], "--sprites-only") == 0) spritesOnly = true;
  }
  std::printf("Particles (hs_particles), %s, load average %s\n\n", hs::bench::threadsText().c_str(),
              hs::bench::loadAverageLine().c_str());

  if (spritesOnly) goto sprites;
  {
  // 1. Evaluation rate.
  std::printf("1. Closed-form frames (gravity, drag, wind; no replay): a frame = enumerate births + evaluate\n");
  std::printf("%10s %8s %12s %14s\n", "particles", "threads", "frame ms", "particles/s");
  for (double n : quick ? std::vector<double>{1e5} : std::vector<double>{1e5, 1e6}) {
    std::string err;
    auto ev = Evaluator::create(fountain(n), {}, err);
    for (int threads : {1, 0}) {
      size_t count = 0;
      const double s = timeIt([&] { count = ev->frame(20.0, nullptr, threads).particles.size(); }, 0.3);
      std::printf("%10zu %8s %12.2f %14.3g\n", count, threads == 1 ? "1" : "all", s * 1e3, double(count) / s);
    }
  }
  {
    EmitterDesc e = fountain(2e4);
    e.turbulence = 5.0;
    e.collision = CollisionMode::Bounce;
    const HeightFieldCollider ground = hills();
    std::string err;
    auto ev = Evaluator::create(e, {nullptr, {&ground}}, err);
    for (int threads : {1, 0}) {
      uint64_t steps = 0;
      const double s = timeIt([&] { steps = ev->frame(20.0, nullptr, threads).replaySteps; }, 0.3);
      std::printf("replay (turbulence + bounce on a height field), %s thread(s): %.3g steps/s (%" PRIu64 " steps, %.1f ms)\n",
                  threads == 1 ? "1" : "all", double(steps) / s, steps, s * 1e3);
    }
  }

  // 2. Integrators: error against run time.
  std::printf("\n2. Error against run time: |x(T) - exact| (max over particles, metres) at T = 2 s,\n"
              "   time per particle for the whole 2 s; gravity (0,0,-9.81), wind (3,1,0), 256 particles\n");
  std::printf("%8s %8s %22s %14s %14s\n", "k /s", "dt s", "integrator", "error m", "us/particle");
  const double T = 2.0;
  const int P = 256;
  std::vector<Kinematics> starts(P);
  for (int i = 0; i < P; ++i) starts[size_t(i)] = {dvec3(0.0), dvec3(std::sin(i * 0.37) * 5, std::cos(i * 0.21) * 5, 3 + (i % 7))};
  std::vector<hs::bench::PlotPanel> panels;
  const Integrator integrators[] = {Integrator::Euler, Integrator::SemiImplicitEuler, Integrator::Rk4, Integrator::Exact};
  const hs::bench::PlotColour colours[] = {{200, 60, 40}, {230, 150, 30}, {40, 110, 200}, {30, 150, 70}};
  const hs::bench::PlotMarker markers[] = {hs::bench::PlotMarker::Circle, hs::bench::PlotMarker::Square,
                                           hs::bench::PlotMarker::Triangle, hs::bench::PlotMarker::Diamond};
  for (double k : {0.0, 1.0, 100.0, 1e4}) {
    const Forces f{{0, 0, -9.81}, k, {3, 1, 0}};
    hs::bench::PlotPanel panel;
    char title[64];
    std::snprintf(title, sizeof title, "drag k = %g /s", k);
    panel.title = title;
    panel.xLabel = "run time per particle (us, 2 s simulated)";
    panel.yLabel = "position error (m)";
    panel.logX = panel.logY = true;
    for (int w = 0; w < 4; ++w) {
      hs::bench::PlotSeries series{integratorName(integrators[w]), colours[w], markers[w], false, {}, {}};
      for (double dt : {1e-3, 1e-2, 1e-1, 1.0}) {
        double err = 0;
        volatile double sink = 0;
        const double s = timeIt([&] {
          for (int i = 0; i < P; ++i) {
            const Kinematics r = integrate(integrators[w], starts[size_t(i)], f, T, dt);
            sink = sink + r.x.x;
          }
        });
        for (int i = 0; i < P; ++i) {
          const Kinematics r = integrate(integrators[w], starts[size_t(i)], f, T, dt);
          const Kinematics ex = exactMotion(starts[size_t(i)], f, T);
          const double e = maxAbs(r.x - ex.x);
          err = std::isfinite(e) ? std::max(err, e) : std::numeric_limits<double>::infinity();
        }
        const double us = s / P * 1e6;
        char errText[32];
        if (!std::isfinite(err) || err > 1e12) std::snprintf(errText, sizeof errText, "unstable");
        else std::snprintf(errText, sizeof errText, "%.3g", err);
        std::printf("%8g %8g %22s %14s %14.3g\n", k, dt, integratorName(integrators[w]), errText, us);
        // The plot: exact errors at rounding level drawn at 1e-16, unstable ones at 1e12.
        const double y = !std::isfinite(err) || err > 1e12 ? 1e12 : std::max(err, 1e-16);
        series.points.push_back({us, y});
        char lbl[16];
        std::snprintf(lbl, sizeof lbl, "%g", dt);
        series.pointLabels.push_back(lbl);
      }
      panel.series.push_back(series);
    }
    panels.push_back(panel);
  }
  if (!plotPath.empty()) {
    const std::string perr = hs::bench::savePlotPng(panels, plotPath, 560, 480);
    if (!perr.empty()) std::fprintf(stderr, "plot: %s\n", perr.c_str());
    else std::printf("plot written to %s (labels: dt in s; errors at or below 1e-16 drawn at 1e-16, unstable at 1e12)\n",
                     plotPath.c_str());
  }

  // 3. Replay error against step size.
  const int burst = quick ? 60 : 200;
  std::printf("\n3. Replay error against a 1e-4 s reference, %d particles (one burst), state at 3 s after birth\n", burst);
  std::printf("%-28s %10s %14s %14s %12s\n", "scenario", "step s", "max error m", "median m", "ms/frame");
  const HeightFieldCollider ground = hills();
  for (int scenario = 0; scenario < 2; ++scenario) {
    EmitterDesc e = fountain(0);
    e.rate = 0;
    e.bursts = {{0.0, burst}};
    e.lifetimeMin = e.lifetimeMax = 10.0;
    e.turbulence = 5.0;
    e.turbulenceFrequency = 0.5;
    e.turbulenceEvolution = 0.3;
    if (scenario == 1) e.collision = CollisionMode::Bounce, e.restitution = 0.6, e.restSpeed = 0.0;
    const char* name = scenario == 0 ? "turbulence" : "turbulence + bounce (hills)";
    EvaluatorInputs in;
    if (scenario == 1) in.colliders = {&ground};
    auto run = [&](double step, double& seconds) {
      EmitterDesc x = e;
      x.replayStep = step;
      std::string err;
      auto ev = Evaluator::create(x, in, err);
      Frame f;
      seconds = timeIt([&] { f = ev->frame(3.0, nullptr, 1); }, 0.0);
      return f;
    };
    double tref = 0;
    const Frame ref = run(1e-4, tref);
    for (double step : {1.0 / 15, 1.0 / 30, 1.0 / 60, 1.0 / 120, 1.0 / 240, 1.0 / 480, 1e-3}) {
      double secs = 0;
      const Frame f = run(step, secs);
      std::vector<double> errs;
      for (size_t i = 0; i < f.particles.size() && i < ref.particles.size(); ++i)
        errs.push_back(glm::length(f.particles[i].position - ref.particles[i].position));
      std::printf("%-28s %10.5f %14.3g %14.3g %12.2f\n", name, step, *std::max_element(errs.begin(), errs.end()),
                  hs::bench::median(errs), secs * 1e3);
    }
    std::printf("%-28s %10.5f %14s %14s %12.2f\n", name, 1e-4, "(reference)", "", tref * 1e3);
  }

  // 4. Cold against warm.
  std::printf("\n4. Frame 30,000 at 60 fps (t = 500 s): cold (no cache) against warm (frame 29,999 in the cache)\n");
  std::printf("%-18s %8s %10s %14s %12s %12s %12s\n", "emitter", "threads", "particles", "cold steps", "cold ms",
              "warm steps", "warm ms");
  PresetOptions o;
  o.area = glm::dvec4(-20, -20, 20, 20);
  o.at = {0, 0, -2.0};
  std::vector<EmitterDesc> es = snowPreset(o);
  for (const EmitterDesc& x : torchPreset(o)) es.push_back(x);
  for (const EmitterDesc& x : dustPreset(o)) es.push_back(x);
  const double t = 30000.0 / 60.0, prev = 29999.0 / 60.0;
  for (const EmitterDesc& x : es) {
    std::string err;
    auto ev = Evaluator::create(x, {nullptr, {&ground}}, err);
    if (!ev) {
      std::printf("%s\n", err.c_str());
      continue;
    }
    for (int threads : {1, 0}) {
      Frame cold, warm;
      const double c = timeIt([&] { cold = ev->frame(t, nullptr, threads); }, 0.0);
      double w = 0;
      for (int rep = 0; rep < 3; ++rep) {
        hs::particles::ReplayCache cache;
        ev->frame(prev, &cache, threads);
        const double t0 = nowSeconds();
        warm = ev->frame(t, &cache, threads);
        const double d = nowSeconds() - t0;
        w = rep == 0 ? d : std::min(w, d);
      }
      bool same = cold.particles.size() == warm.particles.size();
      for (size_t i = 0; same && i < cold.particles.size(); ++i) same = cold.particles[i] == warm.particles[i];
      std::printf("%-18s %8s %10zu %14" PRIu64 " %12.1f %12" PRIu64 " %12.2f%s\n", x.name.c_str(), threads == 1 ? "1" : "all",
                  cold.particles.size(), cold.replaySteps, c * 1e3, warm.replaySteps, w * 1e3,
                  same ? "" : "  MISMATCH");
    }
  }

  }
sprites:
  if (!spriteDir.empty()) {
    auto write = [&](const hs::Image& im, const std::string& file) {
      std::string err;
      const std::string path = spriteDir + "/" + file;
      if (!hs::image_io::writeFile(path, hs::image_io::Spec::of(im.width, im.height, 4, hs::image_io::PixelType::UInt8),
                                   hs::image_io::PixelType::UInt8, im.rgba8.data(), err))
        std::fprintf(stderr, "%s: %s\n", path.c_str(), err.c_str());
      else std::printf("wrote %s\n", path.c_str());
    };
    // Each also over a dark blue sky (straight alpha, composited in sRGB bytes: a preview only).
    auto preview = [](hs::Image im) {
      for (size_t i = 0; i < im.pixelCount(); ++i) {
        uint8_t* p = &im.rgba8[i * 4];
        const int bg[3] = {20, 25, 45};
        for (int c = 0; c < 3; ++c) p[c] = uint8_t((p[c] * p[3] + bg[c] * (255 - p[3]) + 127) / 255);
        p[3] = 255;
      }
      return im;
    };
    const hs::Image flake = snowflakeSprite(128, 1), puff = smokePuffSprite(128, 1);
    const hs::Image flame = flameFlipbook(64, 16, 1).atlas;
    write(flake, "snowflake.png");
    write(puff, "smoke_puff.png");
    write(flame, "flame_flipbook.png");
    write(preview(flake), "snowflake_preview.png");
    write(preview(puff), "smoke_puff_preview.png");
    write(preview(flame), "flame_flipbook_preview.png");
  }
  std::printf("\nload average at the end: %s\n", hs::bench::loadAverageLine().c_str());
  return 0;
}
