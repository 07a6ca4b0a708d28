// bench_post: the post chain's cost per effect (docs/rendering.md
// "Post-processing"), one eye at 1920x1080 by default: a frame of a small
// lit scene with every effect off (the tone map pass alone), then with
// each effect on alone (the LUT at 33^3 and 65^3), then all of them, then
// each stylised effect; per row the GPU time of the post passes (the tone
// map pass, bloom's levels, the stylised passes; timestamp queries), their
// count, and the frame's wall time over the all-off frame's. The all-off
// row against a frame with the tone map only is the claim that the chain
// costs nothing when off: the same pass, the same time. Then the
// anti-aliasing modes (none, FXAA, SMAA, MSAA 4x). Last, a
// transition's frame of each kind (two shots as two view groups, combined
// by weights or a stylised pattern at its middle) against a plain one, and
// a crossfade into a camera graded apart (its own post settings: each
// shot's finished picture combined).
// Automatic exposure: a probe's time against a frame's, and the
// adaptation's error against run time per probe rate (core/exposure_meter.h,
// on a flight's target: a slow swing and a 4 EV step into shade, against
// the same equation sampled 1000 times a second).
//
//   bench_post [--size 1920x1080] [--frames N]
#include <QCoreApplication>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/common/bench_util.h"
#include "core/exposure_meter.h"
#include "core/stipple_layout.h"
#include "render/auto_exposure.h"
#include "mesh/primitives.h"
#include "render/offscreen_renderer.h"
#include "core/content_hash.h"
#include "render/renderer.h"
#include "scene/fields.h"
#include "scene/demo_post.h"
#include "scene/scene_state.h"
#include "sequencer/camera_cuts.h"
#include "sequencer/camera_path.h"
#include "tests/common/scene_parts.h"
#include "tests/common/stipple_reference.h"
#include "tests/common/two_shots.h"

using namespace hs;

namespace {

scene::SceneState baseScene() {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.tonemap = scene::Tonemap::AgX;
  test::addMeshAsset(s, 1, "Ground", mesh::gridPlane(200.0f, 4), {0.4f, 0.4f, 0.38f});
  test::addMeshEntity(s, 1, "Ground", 1);
  test::addMeshAsset(s, 2, "Ball", mesh::uvSphere(1.0f, 32, 16), {0.8f, 0.3f, 0.2f});
  test::addMeshEntity(s, 2, "Ball", 2, {0.0, 0.0, 1.0});
  test::addSun(s, 3, {50, 0, -30});
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  QCoreApplication app(argc, argv);
  int width = 1920, height = 1080, frames = 3;
  for (int i = 1; i + 1 < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames") frames = std::max(1, std::atoi(argv[++i]));
    if (a == "--size" && std::sscanf(argv[i + 1], "%dx%d", &width, &height) == 2) ++i;
  }
  render::OffscreenRenderer r;
  std::string error;
  if (!r.initialize(error)) {
    std::fprintf(stderr, "bench_post: %s\n", error.c_str());
    return 1;
  }
  std::printf("bench_post: %dx%d, %s; %s; load %.2f\n", width, height, r.glDescription().c_str(),
              bench::threadsText().c_str(), bench::loadAverage());
  render::RenderView v;
  v.width = width;
  v.height = height;
  v.fovY = glm::radians(50.0);
  v.eye = {0.0, -8.0, 2.5};
  v.orientation = sequencer::lookRotation(glm::dvec3(0.0, 8.0, -1.5));
  // The demo's LUT (scene/demo_post.h) at two sizes: OpenColorIO's shader
  // with a tetrahedral lookup into a 33^3 or 65^3 3D texture.
  auto lutOf = [](int size) {
    auto bytes = std::make_shared<const std::string>(scene::demoLutCube(size));
    const uint64_t hash = contentHash(bytes->data(), bytes->size());
    return scene::LutData{"bench_" + std::to_string(size) + ".cube", bytes, hash};
  };
  static const scene::LutData lut33 = lutOf(33), lut65 = lutOf(65);
  struct Row {
    const char* name;
    void (*set)(scene::PostSettings&);
  };
  const Row rows[] = {
      {"all off", [](scene::PostSettings&) {}},
      {"bloom", [](scene::PostSettings& p) { p.bloom = true; }},
      {"chromatic aberration", [](scene::PostSettings& p) { p.chromaticAberration = true; }},
      {"grade", [](scene::PostSettings& p) { p.grade = true, p.saturation = 1.2f; }},
      {"vignette", [](scene::PostSettings& p) { p.vignette = true; }},
      {"grain", [](scene::PostSettings& p) { p.grain = true; }},
      {"LUT 33^3", [](scene::PostSettings& p) { p.lut = lut33, p.lutEnabled = true; }},
      {"LUT 65^3", [](scene::PostSettings& p) { p.lut = lut65, p.lutEnabled = true; }},
      {"all on", [](scene::PostSettings& p) {
         p.bloom = p.chromaticAberration = p.grade = p.vignette = p.grain = true;
         p.lut = lut33, p.lutEnabled = true;
       }},
      // The stylised effects (render/passes/stylised_passes.h).
      {"kuwahara r=6", [](scene::PostSettings& p) { p.kuwahara = true; }},
      {"comic", [](scene::PostSettings& p) { p.comic = true; }},
      {"outlines", [](scene::PostSettings& p) { p.outlines = true; }},
      {"crt", [](scene::PostSettings& p) { p.crt = true; }},
      {"dither bayer", [](scene::PostSettings& p) { p.dither = scene::DitherMode::Bayer; }},
      {"dither blue noise", [](scene::PostSettings& p) { p.dither = scene::DitherMode::BlueNoise; }},
      {"dither error diff.", [](scene::PostSettings& p) { p.dither = scene::DitherMode::ErrorDiffusion; }},
      {"outlines+crt+dither", [](scene::PostSettings& p) {
         p.outlines = p.crt = true;
         p.dither = scene::DitherMode::Bayer;
       }},
  };
  std::printf("%-22s %8s %12s %12s %10s\n", "effect", "passes", "post GPU ms", "frame ms", "/all off");
  render::RenderOptions o;
  o.passTimings = true;
  double offFrame = 0.0;
  for (const Row& row : rows) {
    scene::SceneState s = baseScene();
    row.set(s.settings.post);
    std::vector<double> post, wall;
    size_t passes = 0;
    for (int f = 0; f < frames + 1; ++f) {  // the first builds programs
      const double t0 = bench::nowSeconds();
      const render::FrameStats st = r.renderOnly(s, v, o);
      const double ms = (bench::nowSeconds() - t0) * 1e3;
      if (f == 0) continue;
      double gpu = 0.0;
      passes = 0;
      for (const render::PassStats& p : st.passes)
        if (p.name.rfind("tonemap", 0) == 0 || p.name.rfind("bloom", 0) == 0 || p.name.rfind("kuwahara", 0) == 0 ||
            p.name.rfind("stylise", 0) == 0 || p.name.rfind("blue_noise", 0) == 0 ||
            p.name.rfind("error_diffusion", 0) == 0 || p.name.rfind("dither_copy", 0) == 0) {
          gpu += std::max(0.0, p.gpuMs);
          ++passes;
        }
      post.push_back(gpu);
      wall.push_back(ms);
    }
    const double frame = bench::median(wall);
    if (offFrame == 0.0) offFrame = frame;
    std::printf("%-22s %8zu %12.2f %12.1f %10.3f\n", row.name, passes, bench::median(post), frame, frame / offFrame);
    std::fflush(stdout);
  }
  // Anti-aliasing (settings.antialiasing): the frame and the GPU time of
  // the filter's passes (FXAA's one, SMAA's three) against none; MSAA's cost
  // is in the scene passes (4 samples), so only its frame time says it.
  {
    std::printf("\n%-22s %12s %12s %10s\n", "anti-aliasing", "AA GPU ms", "frame ms", "/none");
    double none = 0.0;
    for (const auto& [name, aa] : {std::pair{"none", scene::Antialiasing::None}, std::pair{"FXAA", scene::Antialiasing::Fxaa},
                                   std::pair{"SMAA", scene::Antialiasing::Smaa},
                                   std::pair{"MSAA 4x", scene::Antialiasing::Msaa4}}) {
      scene::SceneState s = baseScene();
      s.settings.antialiasing = aa;
      std::vector<double> gpu, wall;
      for (int f = 0; f < frames + 1; ++f) {
        const double t0 = bench::nowSeconds();
        const render::FrameStats st = r.renderOnly(s, v, o);
        const double ms = (bench::nowSeconds() - t0) * 1e3;
        if (f == 0) continue;
        double g = 0.0;
        for (const render::PassStats& p : st.passes)
          if (p.name.rfind("fxaa", 0) == 0 || p.name.rfind("smaa", 0) == 0) g += std::max(0.0, p.gpuMs);
        gpu.push_back(g);
        wall.push_back(ms);
      }
      const double frame = bench::median(wall);
      if (none == 0.0) none = frame;
      std::printf("%-22s %12.2f %12.1f %10.3f\n", name, bench::median(gpu), frame, frame / none);
      std::fflush(stdout);
    }
  }
  // Weighted Voronoi stippling (render/passes/stipple_passes.h): its
  // passes' GPU time and the frame per count of Lloyd steps, against the
  // frame without it, and the error those steps leave: the sites' mean
  // distance to their cells' darkness-weighted centroids (0 at a centroidal
  // tessellation), from the CPU twin (exact cells) on this frame's picture.
  {
    const render::RenderView sv = v;
    const scene::SceneState plain = baseScene();
    const Image picture = r.render(plain, sv);
    const StippleLayout layout = stippleLayout(plain.settings.post.stippleSpacingPx, plain.settings.post.stippleDotPx,
                                               sv.width, sv.height);
    std::printf("\n%-22s %12s %12s %10s %16s %14s\n", "stippling", "GPU ms", "frame ms", "/none", "centroid gap",
                "vs exact cells");
    double none = 0.0;
    for (int steps : {-1, 0, 1, 2, 4, 8, 16}) {
      scene::SceneState s = plain;
      s.settings.post.stipple = steps >= 0;
      s.settings.post.stippleIterations = std::max(steps, 0);
      std::vector<double> gpu, wall;
      for (int f = 0; f < frames + 1; ++f) {
        const double t0 = bench::nowSeconds();
        const render::FrameStats st = r.renderOnly(s, sv, o);
        const double ms = (bench::nowSeconds() - t0) * 1e3;
        if (f == 0) continue;
        double g = 0.0;
        for (const render::PassStats& p : st.passes)
          if (p.name.rfind("stipple", 0) == 0) g += std::max(0.0, p.gpuMs);
        gpu.push_back(g);
        wall.push_back(ms);
      }
      const double frame = bench::median(wall);
      if (none == 0.0) none = frame;
      const std::string name = steps < 0 ? "off" : std::to_string(steps) + " steps";
      // The twin after as many steps: its distance to the centroids, and the
      // share of pixels more than 8/255 from its dots (exact cells where the
      // renderer floods): jump flooding's error.
      double differ = 0.0, gap = 0.0;
      if (steps >= 0) {
        const Image dots = r.render(s, sv);
        const test::StippleTwin twin = test::stippleTwin(picture, layout, steps);
        gap = twin.centroidGap;
        const Image exact = test::stippledPicture(twin, sv.width, sv.height);
        size_t off = 0;
        for (size_t i = 0; i < dots.pixelCount(); ++i) off += std::abs(int(dots.rgba8[i * 4]) - int(exact.rgba8[i * 4])) > 8;
        differ = 100.0 * double(off) / double(dots.pixelCount());
      }
      std::printf("%-22s %12.2f %12.1f %10.3f %13.4f cells %13.3f%%\n", name.c_str(), bench::median(gpu), frame,
                  frame / none, gap, differ);
      std::fflush(stdout);
    }
    std::printf("(%u candidates on a %dx%d grid, spacing %.2f cells)\n", layout.candidates, layout.gridWidth,
                layout.gridHeight, double(layout.spacingCells));
    // A stereo pair at 8 steps: the second eye reprojects the first eye's
    // dots by depth and relaxes only its own in the holes.
    scene::SceneState s = plain;
    s.settings.post.stipple = true;
    s.settings.post.stippleIterations = 8;
    const render::RenderView left = test::shiftedSideways(sv, -0.032), right = test::shiftedSideways(sv, 0.032);
    std::vector<double> first, second;
    for (int f = 0; f < frames + 1; ++f) {
      const render::FrameStats st = r.renderViewsOnly(s, {left, right}, o);
      if (f == 0) continue;
      double a = 0.0, b = 0.0;
      for (const render::PassStats& p : st.passes)
        if (p.name.rfind("stipple", 0) == 0) (p.name.find("right") != std::string::npos ? b : a) += std::max(0.0, p.gpuMs);
      first.push_back(a);
      second.push_back(b);
    }
    std::printf("%-22s %12.2f   (first eye %.2f: the second eye's dots reprojected from it)\n", "8 steps, second eye",
                bench::median(second), bench::median(first));
  }
  // Transition frames (sequencer/camera_cuts.h): both shots rendered as
  // two view groups and combined (a weighted sum, or a stylised
  // transition's pattern at its middle), against one shot's frame; both
  // read back.
  {
    render::RenderView other = v;
    other.eye = {6.0, -6.0, 3.0};
    other.orientation = sequencer::lookRotation(glm::dvec3(-6.0, 6.0, -2.0));
    const scene::SceneState s = baseScene();
    // The incoming shot through a camera with its own grade
    // (scene/camera_post.h): the chains differ, so each shot runs its own
    // and the finished pictures are combined (two copies, one combine).
    scene::SceneState graded = s;
    constexpr scene::EntityId kGraded = 9001;
    scene::Entity cam;
    cam.id = kGraded;
    cam.name = "Graded camera";
    cam.camera = scene::Camera{};
    scene::findEntityField("camera.post.grade.enabled")->set(cam, true);
    scene::findEntityField("camera.post.grade.temperature")->set(cam, -0.3);
    graded.entities.emplace(kGraded, cam);
    graded.roots.push_back(kGraded);
    render::RenderView otherGraded = other;
    otherGraded.camera = kGraded;
    std::printf("\n%-22s %12s %12s %10s %14s\n", "transition frame", "plain ms", "transition", "/plain", "combine GPU ms");
    const auto row = [&](const std::string& label, const scene::SceneState& state, const render::RenderView& in,
                         sequencer::Transition t) {
      const render::GroupCombine pattern = render::combineOf(sequencer::Shot{0, 1, t, 0.5}, 7);
      const auto [w0, w1] = std::pair{pattern.weights[0], pattern.weights[1]};
      std::vector<double> plain, mixed, combine;
      for (int f = 0; f < frames + 1; ++f) {
        double t0 = bench::nowSeconds();
        r.render(state, v, false, nullptr, o);
        const double one = (bench::nowSeconds() - t0) * 1e3;
        t0 = bench::nowSeconds();
        render::FrameStats st;
        r.renderMix(state, {v, in}, {w0, w1}, false, &st, o, &pattern);
        const double two = (bench::nowSeconds() - t0) * 1e3;
        if (f == 0) continue;
        plain.push_back(one);
        mixed.push_back(two);
        double gpu = 0.0;
        for (const render::PassStats& p : st.passes)
          if (p.name.rfind("group_combine", 0) == 0 || p.name.rfind("picture_combine", 0) == 0 ||
              p.name.find("_picture_copy") != std::string::npos)
            gpu += std::max(0.0, p.gpuMs);
        combine.push_back(gpu);
      }
      std::printf("%-22s %12.1f %12.1f %10.3f %14.2f\n", label.c_str(), bench::median(plain), bench::median(mixed),
                  bench::median(mixed) / bench::median(plain), bench::median(combine));
      std::fflush(stdout);
    };
    for (const std::string& name : sequencer::transitionNameList()) {
      const sequencer::Transition t = *sequencer::transitionFromName(name);
      if (t != sequencer::Transition::Cut) row(name, s, other, t);
    }
    row("crossfade, graded apart", graded, otherGraded, sequencer::Transition::Crossfade);
  }
  // Automatic exposure (render/auto_exposure.h): one probe (72 rows) per
  // grid step; a sequence renders probes_per_second of them per second of
  // film, a still its whole window.
  {
    scene::SceneState s = baseScene();
    s.settings.post.autoExposure = true;
    render::AutoExposure ae;
    std::vector<double> probe, frame;
    for (int f = 0; f < frames + 1; ++f) {
      double t0 = bench::nowSeconds();
      ae.viewEv100(r.renderer(), s, v);  // a probe
      const double p = (bench::nowSeconds() - t0) * 1e3;
      t0 = bench::nowSeconds();
      r.renderOnly(s, v);
      const double one = (bench::nowSeconds() - t0) * 1e3;
      if (f == 0) continue;
      probe.push_back(p);
      frame.push_back(one);
    }
    ae.release();
    const double probeMs = bench::median(probe), frameMs = bench::median(frame);
    std::printf("\nautomatic exposure: probe %dx%d %.1f ms, frame %.1f ms (probe/frame %.3f)\n",
                int(std::lround(render::AutoExposure::kProbeRows * v.aspect())), render::AutoExposure::kProbeRows,
                probeMs, frameMs, probeMs / frameMs);
    // The adaptation's error per probe rate on a flight's target: a swing of
    // ±2 EV over 8 s and a 4 EV step into shade at 5.1 s; the reference is
    // the same equation sampled 1000 times a second. Speeds: the defaults.
    auto flight = [](double t) { return 12.0 + 2.0 * std::sin(0.8 * t) - (t >= 5.1 ? 4.0 : 0.0); };
    auto adapted = [&](double rate, double t) {
      ExposureAdaptation a;
      a.probesPerSecond = rate;
      a.maxProbes = 1 << 20;
      return adaptedEv100(t, a, [&](int64_t g) { return flight(double(g) / rate); });
    };
    std::printf("%-10s %12s %12s %16s %16s %14s %12s\n", "probes/s", "max err EV", "mean err EV", "probes/frame@60",
                "seq. ms/frame", "still probes", "still ms");
    for (double rate : {1.0, 2.0, 4.0, 8.0, 16.0, 30.0}) {
      double worst = 0.0, sum = 0.0;
      int n = 0;
      for (double t = 0.0; t <= 12.0; t += 1.0 / 60.0, ++n) {
        const double e = std::abs(adapted(rate, t) - adapted(1000.0, t));
        worst = std::max(worst, e);
        sum += e;
      }
      ExposureAdaptation a;
      a.probesPerSecond = rate;
      const AdaptationWindow w = adaptationWindow(60.0, a);
      const double stillProbes = double(w.last - w.first + 1);
      std::printf("%-10.0f %12.3f %12.4f %16.3f %16.2f %14.0f %12.0f\n", rate, worst, sum / n, rate / 60.0,
                  rate / 60.0 * probeMs, stillProbes, stillProbes * probeMs);
    }
  }
  return 0;
}
