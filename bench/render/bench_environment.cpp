// bench_environment: the analytic sky's image-based light (render/
// environment_maps.h), error against run time as every approximation
// reports it.
//
// Accuracy: the irradiance E(n)/pi from spherical harmonics (bands 0-1: 4
// coefficients; bands 0-2: 9, what the renderer keeps) projected from a
// cube of N x N texels per face, against a brute-force integral of the same
// sky (render/sh_irradiance.h, 96 x 192 cells over each hemisphere), over
// 256 normals spread over the sphere, at three sun heights. The projection
// here is the CPU twin of shaders/env_sh.comp (tests/render/test_sky_render
// checks the GPU's coefficients against it within 0.5%), so cube sizes the
// renderer does not ship can be compared; its CPU time is the column "cpu ms".
//
// Cost on the GPU: the environment pass (sky cube, SH, prefiltered
// specular) at the shipped sizes, and the sky pass at 1920x1080, from GPU
// timestamps (RenderOptions::passTimings), median of N frames, each frame
// with a slightly moved sun so the pass runs every time.
//
//   bench_environment [--frames N]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <thread>
#include <vector>

#include "bench/common/bench_util.h"
#include "render/environment_maps.h"
#include "render/offscreen_renderer.h"
#include "render/sh_irradiance.h"
#include "render/sky_model.h"

using namespace hs;

namespace {

std::vector<glm::dvec3> spreadNormals(int n) {
  // A Fibonacci sphere: near-uniform, deterministic.
  std::vector<glm::dvec3> out;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), a = golden * i;
    out.push_back({r * std::cos(a), r * std::sin(a), z});
  }
  return out;
}

glm::dvec3 sunTowards(double elevationDeg) {
  const double e = glm::radians(elevationDeg);
  return {std::cos(e) * 0.5736, -std::cos(e) * 0.8192, std::sin(e)};
}

double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

void accuracyTable() {
  const std::vector<glm::dvec3> normals = spreadNormals(256);
  std::printf("\nSH irradiance against brute force (relative error of luminance over %zu normals)\n",
              normals.size());
  std::printf("%-9s %-6s %-8s %10s %10s %10s %10s\n", "sun", "cube", "cpu ms", "4 mean%", "4 max%", "9 mean%",
              "9 max%");
  for (double elevation : {60.0, 20.0, 5.0}) {
    const render::PreethamSky sky = render::PreethamSky::make(sunTowards(elevation), 3.0, 0.2);
    const render::RadianceFn radiance = [&](const glm::dvec3& d) { return sky.radiance(d); };
    std::vector<double> reference;
    for (const glm::dvec3& n : normals) reference.push_back(luminance(render::bruteForceIrradiance(radiance, n, 96)));
    for (int size : {4, 8, 16, 32, 64}) {
      const double t0 = bench::nowSeconds();
      const auto L = render::projectCube(radiance, size);
      const double ms = (bench::nowSeconds() - t0) * 1e3;
      double mean[2] = {0, 0}, worst[2] = {0, 0};
      for (size_t i = 0; i < normals.size(); ++i)
        for (int k = 0; k < 2; ++k) {
          const double e = std::abs(luminance(render::shIrradiance(L, normals[i], k + 1)) - reference[i]) / reference[i];
          mean[k] += e / double(normals.size());
          worst[k] = std::max(worst[k], e);
        }
      std::printf("%-9s %-6d %-8.2f %10.2f %10.2f %10.2f %10.2f\n", (std::to_string(int(elevation)) + " deg").c_str(),
                  size, ms, mean[0] * 100, worst[0] * 100, mean[1] * 100, worst[1] * 100);
    }
  }
}

void gpuTable(int frames) {
  render::OffscreenRenderer r;
  std::string error;
  if (!r.initialize(error)) {
    std::printf("\nno GPU table: %s\n", error.c_str());
    return;
  }
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.sky = scene::SkyModel::Analytic;
  scene::Entity sun;
  sun.id = 1;
  sun.name = "Sun";
  sun.light = scene::Light{};
  s.entities.emplace(1, sun);
  s.roots.push_back(1);
  render::RenderView view;
  view.width = 1920;
  view.height = 1080;
  view.fovY = glm::radians(50.0);
  view.orientation = glm::dquat(glm::dvec3(glm::radians(80.0), 0.0, 0.0));  // towards the horizon
  render::RenderOptions o;
  o.passTimings = true;
  std::vector<double> env, sky;
  for (int f = 0; f < frames + 2; ++f) {
    s.entities.at(1).transform.rotation = glm::dquat(glm::dvec3(glm::radians(40.0 + 0.1 * f), 0.0, 0.3));
    const render::FrameStats st = r.renderOnly(s, view, o);
    if (f < 2) continue;  // warm-up
    for (const auto& p : st.passes) {
      if (p.name == "environment") env.push_back(p.gpuMs);
      if (p.name == "sky") sky.push_back(p.gpuMs);
    }
  }
  size_t envBytes = 0;
  for (const auto& a : r.renderer().resourceRegistry())
    if (a.name.rfind("environment_", 0) == 0) envBytes += a.bytes;
  std::printf("\nGPU, median of %d frames (%s)\n", frames, r.glDescription().c_str());
  std::printf("environment pass (radiance cube %d^2 + mips, 9 SH, specular %d^2 x %d levels): %.2f ms, %zu bytes\n",
              render::EnvironmentMaps::kRadianceSize, render::EnvironmentMaps::kSpecularSize,
              render::EnvironmentMaps::kSpecularLevels, bench::median(env), envBytes);
  std::printf("analytic sky pass at 1920x1080 (every pixel sky): %.2f ms\n", bench::median(sky));
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 9;
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) frames = std::max(1, std::atoi(argv[++i]));
  std::printf("bench_environment, load %s, %s\n", bench::loadAverageLine().c_str(),
              bench::threadsText().c_str());
  accuracyTable();
  gpuTable(frames);
  std::printf("load after: %s\n", bench::loadAverageLine().c_str());
  return 0;
}
