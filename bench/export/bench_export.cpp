// bench_export: what exporting the 10-minute stereo film costs, measured on
// a sample and extrapolated to 36,000 side-by-side 3840x1080 frames.
//
//   build/bench/export/bench_export [--frames N] [--render-ms MS] [--video-frames N] [--out DIR]
//
// This benchmark measures the export loop and the writers alone, so frames
// come from a synthetic source (bench_export_render measures the real
// renderer): crops of a procedural valley image (sky,
// fbm terrain, fine grain, so encoders see realistic detail), one crop per
// eye with a disparity shift, moving every frame. "Render" time is that
// copy plus a fresh grain per frame (renders are not pure translations of
// one picture, and video encoders would otherwise find perfect matches), and
// in table 3 --render-ms of sleep standing in for a GPU that renders while
// the CPU encodes (default 100 ms). Tables:
//   1. encode-only per format: ms per frame, bytes per frame
//   2. export frames per second per format with 1 and 2 writer threads
//   3. render-only, encode-only, both in turn, and the overlapped export
//   4. ffmpeg H.264 / H.265 throughput (raw frames piped to ffmpeg)
//   5. the whole film extrapolated from the measured rates, next to the
//      reference pipeline's 7 h render + 15 h re-encode
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <sys/resource.h>

#include "bench/common/bench_util.h"
#include "core/lowbias32.h"
#include "sequencer/export_loop.h"
#include "sequencer/ffmpeg_writer.h"
#include "sequencer/image_writer.h"
#include "sequencer/stereo_layout.h"

using namespace hs::sequencer;
using hs::Image;
using hs::ImageView;
namespace fs = std::filesystem;
using hs::bench::cpuSeconds;
using hs::bench::loadAverage;
using Clock = std::chrono::steady_clock;

namespace {

double seconds(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

constexpr int kCores = 2;  // the project's machines

uint32_t hash(uint32_t x) { return hs::lowbias32(x); }

float lattice(int x, int y, uint32_t seed) {
  return float(hash(uint32_t(x) * 73856093U ^ uint32_t(y) * 19349663U ^ seed) & 0xffff) / 65535.0f;
}

float valueNoise(float x, float y, uint32_t seed) {
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  float fx = x - float(x0), fy = y - float(y0);
  fx = fx * fx * (3 - 2 * fx);
  fy = fy * fy * (3 - 2 * fy);
  const float a = lattice(x0, y0, seed), b = lattice(x0 + 1, y0, seed);
  const float c = lattice(x0, y0 + 1, seed), d = lattice(x0 + 1, y0 + 1, seed);
  return (a + (b - a) * fx) + ((c + (d - c) * fx) - (a + (b - a) * fx)) * fy;
}

float fbm(float x, float y, uint32_t seed, int octaves) {
  float sum = 0, amp = 0.5f, freq = 1.0f;
  for (int i = 0; i < octaves; ++i) {
    sum += amp * valueNoise(x * freq, y * freq, seed + uint32_t(i) * 101U);
    amp *= 0.5f;
    freq *= 2.0f;
  }
  return sum;
}

// The procedural valley the synthetic renderer crops from.
struct Valley {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
  Valley(int w, int h) : width(w), height(h), rgba(size_t(w) * size_t(h) * 4) {
    std::vector<std::thread> pool;
    const int threads = std::max(1u, std::thread::hardware_concurrency());
    for (int t = 0; t < threads; ++t)
      pool.emplace_back([&, t] {
        for (int y = t; y < h; y += threads)
          for (int x = 0; x < w; ++x) {
            const float u = float(x) / 300.0f;
            const float horizon = 0.45f * float(h) + 0.25f * float(h) * (fbm(u, 0.5f, 7, 5) - 0.5f) * 2.0f;
            float r, g, b;
            if (float(y) < horizon) {  // sky with clouds
              const float t2 = float(y) / horizon;
              const float cloud = std::max(0.0f, fbm(float(x) / 220.0f, float(y) / 90.0f, 3, 5) - 0.55f) * 2.5f;
              r = 0.35f + 0.4f * t2 + cloud;
              g = 0.55f + 0.3f * t2 + cloud;
              b = 0.9f + 0.05f * t2 + cloud;
            } else {  // rock pillars and grass, detail at every scale
              const float n = fbm(float(x) / 60.0f, float(y) / 60.0f, 11, 7);
              const float rock = fbm(float(x) / 25.0f, float(y) / 140.0f, 5, 4);
              const float depth = (float(y) - horizon) / (float(h) - horizon);
              r = 0.25f + 0.35f * rock + 0.2f * n;
              g = 0.3f + 0.25f * n + 0.15f * (1 - rock) * depth;
              b = 0.2f + 0.2f * rock;
            }
            const float grain = (float(hash(uint32_t(x) * 2654435761U + uint32_t(y)) & 255) / 255.0f - 0.5f) * 0.03f;
            const size_t i = (size_t(y) * size_t(w) + size_t(x)) * 4;
            rgba[i] = uint8_t(std::clamp(r + grain, 0.0f, 1.0f) * 255.0f);
            rgba[i + 1] = uint8_t(std::clamp(g + grain, 0.0f, 1.0f) * 255.0f);
            rgba[i + 2] = uint8_t(std::clamp(b + grain, 0.0f, 1.0f) * 255.0f);
            rgba[i + 3] = 255;
          }
      });
    for (auto& t : pool) t.join();
  }
};

struct Synthetic {
  const Valley& valley;
  int renderMs = 0;
  // One eye: a crop moving 3 px a frame; the right eye sees it 12 px shifted.
  void eye(const FrameJob& job, int which, Image& out) const {
    out = Image::make8(job.eyeWidth, job.eyeHeight);
    const int x0 = int((job.frame * 3 + which * 12) % (valley.width - job.eyeWidth));
    for (int y = 0; y < job.eyeHeight; ++y)
      std::memcpy(&out.rgba8[size_t(y) * size_t(job.eyeWidth) * 4],
                  &valley.rgba[(size_t(y) * size_t(valley.width) + size_t(x0)) * 4], size_t(job.eyeWidth) * 4);
    // Per-frame grain of -1..+1 levels on a quarter of the pixels.
    uint32_t state = hash(uint32_t(job.frame) * 2u + uint32_t(which) + 1u);
    for (size_t i = 0; i < out.rgba8.size(); i += 4) {
      state = state * 1664525u + 1013904223u;
      const uint32_t r = state >> 28;
      if (r < 2) out.rgba8[i + (state >> 20 & 1)] += uint8_t(r == 0 ? 1 : 255);  // wraps only at 0/255, rare
    }
    if (job.floatPixels) {
      Image f = Image::makeF(job.eyeWidth, job.eyeHeight);
      for (size_t i = 0; i < out.rgba8.size(); ++i) f.rgbaF[i] = std::pow(float(out.rgba8[i]) / 255.0f, 2.2f);
      out = std::move(f);
    }
  }
  bool render(const FrameJob& job, EyeImages& out, std::string&) const {
    if (renderMs > 0) std::this_thread::sleep_for(std::chrono::milliseconds(renderMs));  // the GPU's share
    eye(job, 0, out.left);
    if (job.bothEyes) eye(job, 1, out.right);
    return true;
  }
};

FrameJob jobFor(int64_t frame, bool floatPixels = false) {
  FrameJob j;
  j.frame = frame;
  j.eyeWidth = 1920;
  j.eyeHeight = 1080;
  j.floatPixels = floatPixels;
  return j;
}

std::string hms(double s) {
  char buf[64];
  const int h = int(s / 3600), m = int(std::fmod(s, 3600) / 60);
  std::snprintf(buf, sizeof buf, "%dh %02dm", h, m);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  int sample = 12, renderMs = 100, videoFrames = 60;
  std::string outDir = (fs::temp_directory_path() / "hs-bench-export").string();
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--frames")) sample = std::max(2, std::atoi(argv[i + 1]));
    else if (!std::strcmp(argv[i], "--render-ms")) renderMs = std::max(0, std::atoi(argv[i + 1]));
    else if (!std::strcmp(argv[i], "--video-frames")) videoFrames = std::max(2, std::atoi(argv[i + 1]));
    else if (!std::strcmp(argv[i], "--out")) outDir = argv[i + 1];
  }
  fs::remove_all(outDir);
  fs::create_directories(outDir);
  constexpr double kFilm = 36000.0, kReferenceHours = 7.0 + 15.0;

  std::printf("bench_export: side-by-side 3840x1080 frames (two 1920x1080 eyes), %d-frame samples\n", sample);
  std::printf("machine: %s, load average %.2f at start; output in %s\n",
              hs::bench::threadsText().c_str(), loadAverage(), outDir.c_str());
  auto t0 = Clock::now();
  const Valley valley(4800, 1080);
  std::printf("synthetic valley image built in %.2f s (stands in for render/; bench_export_render measures it)\n\n", seconds(t0));
  const Synthetic cpuOnly{valley, 0};

  // 1. Encode-only per format.
  struct Format {
    const char* name;
    const char* ext;
    bool png16, floatPixels;
    int pngLevel;
  } formats[] = {{"PNG 8-bit (zlib 1)", "png", false, false, 1}, {"PNG 8-bit (zlib 6)", "png", false, false, 6},
                 {"PNG 16-bit (zlib 1)", "png", true, false, 1}, {"EXR half (zip)", "exr", false, true, 1},
                 {"JPEG q92", "jpg", false, false, 1},          {"TIFF 8-bit (zip)", "tif", false, false, 1}};
  std::printf("1. Encode only, one call at a time, per 3840x1080 frame (median of %d frames)\n", std::min(sample, 6));
  std::printf("| format              | encode ms | encode CPU ms | write ms | bytes/frame | MB/s (raw RGBA in, CPU) |\n");
  std::printf("|---------------------|----------:|--------------:|---------:|------------:|------------------------:|\n");
  for (const Format& f : formats) {
    std::vector<double> enc, encCpu, wr, sizes;
    for (int i = 0; i < std::min(sample, 6); ++i) {
      EyeImages eyes;
      std::string err;
      cpuOnly.render(jobFor(i, f.floatPixels), eyes, err);
      const Image frame = composeLayout(StereoLayout::SideBySide, eyes.left, eyes.right)[0];
      std::vector<uint8_t> bytes;
      WriteOptions o;
      o.png16 = f.png16;
      o.pngCompression = f.pngLevel;
      auto e0 = Clock::now();
      // Process CPU, not thread CPU: OpenEXR compresses on its own threads.
      const double c0 = cpuSeconds(RUSAGE_SELF);
      if (!encodeImage(*imageFormatFromPath(std::string("x.") + f.ext), frame.view(), bytes, err, o)) {
        std::fprintf(stderr, "%s\n", err.c_str());
        return 1;
      }
      enc.push_back(seconds(e0));
      encCpu.push_back(cpuSeconds(RUSAGE_SELF) - c0);
      e0 = Clock::now();
      writeFileAtomically(outDir + "/enc_" + std::to_string(i) + "." + f.ext, bytes, err);
      wr.push_back(seconds(e0));
      sizes.push_back(double(bytes.size()));
    }
    std::sort(enc.begin(), enc.end());
    std::sort(encCpu.begin(), encCpu.end());
    std::sort(wr.begin(), wr.end());
    double avgSize = 0;
    for (double s : sizes) avgSize += s / double(sizes.size());
    const double e = enc[enc.size() / 2], ec = encCpu[encCpu.size() / 2], w = wr[wr.size() / 2];
    std::printf("| %-19s | %9.1f | %13.1f | %8.1f | %11.0f | %23.1f |\n", f.name, e * 1e3, ec * 1e3, w * 1e3, avgSize,
                3840.0 * 1080 * 4 / ec / 1e6);
  }

  // 2. Export throughput per format, 1 and 2 writers, render = the copy only.
  std::printf("\n2. Export, frames per second, %d frames per run (render: the synthetic copy only, so writers bound it)\n",
              sample);
  std::printf("| format              | 1 writer fps | 2 writers fps | 2 vs 1 | CPU s/frame | idle 2-core fps (est.) |\n");
  std::printf("|---------------------|-------------:|--------------:|-------:|------------:|-----------------------:|\n");
  std::vector<double> exportFps2, exportCpu;
  auto exportRun = [&](const Synthetic& src, const Format& f, int threads, const std::string& sub) {
    ExportSettings s;
    s.frames = FrameList::range(0, sample - 1);
    fs::create_directories(outDir + "/" + sub);
    s.output = outDir + "/" + sub + "/f_%05d." + f.ext;
    s.writerThreads = threads;
    s.resume = false;
    s.image.png16 = f.png16;
    s.image.pngCompression = f.pngLevel;
    auto source = makeCallbackSource([&](const FrameJob& j, EyeImages& o, std::string& e) { return src.render(j, o, e); });
    const ExportResult r = runExport(s, *source);
    if (!r.ok) std::fprintf(stderr, "export failed: %s\n", r.error.c_str());
    return r;
  };
  for (const Format& f : formats) {
    const ExportResult one = exportRun(cpuOnly, f, 1, std::string("x1") + f.ext);
    const double c0 = cpuSeconds(RUSAGE_SELF);
    const ExportResult two = exportRun(cpuOnly, f, 2, std::string("x2") + f.ext);
    const double cpu = (cpuSeconds(RUSAGE_SELF) - c0) / sample;
    const double fps1 = sample / one.seconds, fps2 = sample / two.seconds;
    exportFps2.push_back(fps2);
    exportCpu.push_back(cpu);
    std::printf("| %-19s | %12.2f | %13.2f | %5.2fx | %11.3f | %22.2f |\n", f.name, fps1, fps2, fps2 / fps1, cpu,
                kCores / cpu);
  }

  // 3. Render, encode, in turn, export.
  std::printf("\n3. Overlap: %d PNG 8-bit (zlib 1) frames with a stand-in GPU render of %d ms a frame (sleep + copy)\n",
              sample, renderMs);
  const Synthetic gpuLike{valley, renderMs};
  double renderOnly = 0, encodeOnly = 0;
  {
    auto r0 = Clock::now();
    std::vector<Image> frames;
    for (int i = 0; i < sample; ++i) {
      EyeImages eyes;
      std::string err;
      gpuLike.render(jobFor(i), eyes, err);
      frames.push_back(std::move(eyes.left));
      frames.push_back(std::move(eyes.right));
    }
    renderOnly = seconds(r0) / sample;
    auto e0 = Clock::now();
    for (int i = 0; i < sample; ++i) {
      std::string err;
      const Image sbs = composeLayout(StereoLayout::SideBySide, frames[size_t(2 * i)], frames[size_t(2 * i + 1)])[0];
      WriteOptions o;
      writeImage(outDir + "/seq_" + std::to_string(i) + ".png", sbs.view(), err, o);
    }
    encodeOnly = seconds(e0) / sample;
  }
  std::printf("| pipeline                              | s/frame | frames/s | vs in turn |\n");
  std::printf("|---------------------------------------|--------:|---------:|-----------:|\n");
  const double inTurn = renderOnly + encodeOnly;
  std::printf("| render only                           | %7.3f | %8.2f |            |\n", renderOnly, 1 / renderOnly);
  std::printf("| encode only (compose+PNG+write)       | %7.3f | %8.2f |            |\n", encodeOnly, 1 / encodeOnly);
  std::printf("| render then encode, in turn           | %7.3f | %8.2f |      1.00x |\n", inTurn, 1 / inTurn);
  double export1 = 0, export2 = 0;
  for (int threads : {1, 2}) {
    const ExportResult r = exportRun(gpuLike, formats[0], threads, "overlap" + std::to_string(threads));
    const double perFrame = r.seconds / sample;
    (threads == 1 ? export1 : export2) = perFrame;
    std::printf("| export, %d writer thread%s              | %7.3f | %8.2f | %9.2fx |\n", threads, threads == 1 ? " " : "s",
                perFrame, 1 / perFrame, inTurn / perFrame);
  }
  const double larger = std::max(renderOnly, encodeOnly);
  std::printf("export with 1 writer is %+.0f%% from the larger of render and encode (%.3f s); with 2 writers %+.0f%%\n",
              (export1 / larger - 1) * 100, larger, (export2 / larger - 1) * 100);

  // 4. ffmpeg.
  std::printf("\n4. Direct video through ffmpeg (raw RGBA piped in, %d frames, frames already in memory)\n", videoFrames);
  struct VideoRow {
    const char* name;
    VideoCodec codec;
    const char* preset;
    const char* ext;
    double perFrame = 0, bytes = 0, cpu = 0;
  };
  std::vector<VideoRow> videos = {{"H.264 medium crf18 MP4", VideoCodec::H264, "medium", "mp4"},
                                  {"H.264 veryfast crf18 MP4", VideoCodec::H264, "veryfast", "mp4"},
                                  {"H.265 medium crf18 MKV", VideoCodec::H265, "medium", "mkv"},
                                  {"H.265 fast crf18 MKV", VideoCodec::H265, "fast", "mkv"}};
  if (!ffmpegAvailable()) {
    std::printf("ffmpeg not installed: skipped (apt-get install ffmpeg)\n");
    videos.clear();
  } else {
    std::vector<Image> sbs;
    for (int i = 0; i < std::min(videoFrames, 30); ++i) {
      EyeImages eyes;
      std::string err;
      cpuOnly.render(jobFor(i), eyes, err);
      sbs.push_back(composeLayout(StereoLayout::SideBySide, eyes.left, eyes.right)[0]);
    }
    std::printf("| codec and preset         | s/frame | frames/s | CPU s/frame | idle 2-core fps (est.) | bytes/frame | Mbit/s at 60 fps |\n");
    std::printf("|--------------------------|--------:|---------:|------------:|-----------------------:|------------:|-----------------:|\n");
    for (VideoRow& v : videos) {
      VideoSettings vs;
      vs.codec = v.codec;
      vs.preset = v.preset;
      vs.width = 3840;
      vs.height = 1080;
      const int n = v.codec == VideoCodec::H265 && std::string(v.preset) == "medium" ? std::min(videoFrames, 30) : videoFrames;
      std::string err;
      const std::string path = outDir + "/film_" + v.preset + "." + v.ext;
      auto v0 = Clock::now();
      const double c0 = cpuSeconds(RUSAGE_SELF) + cpuSeconds(RUSAGE_CHILDREN);
      auto w = VideoWriter::open(path, vs, err);
      bool ok = bool(w);
      for (int i = 0; ok && i < n; ++i) ok = w->writeFrame(sbs[size_t(i) % sbs.size()], err);
      ok = ok && w->close(err);
      if (!ok) {
        std::printf("| %-24s | failed: %s\n", v.name, err.c_str());
        continue;
      }
      v.perFrame = seconds(v0) / n;
      v.cpu = (cpuSeconds(RUSAGE_SELF) + cpuSeconds(RUSAGE_CHILDREN) - c0) / n;
      v.bytes = double(fs::file_size(path)) / n;
      std::printf("| %-24s | %7.3f | %8.2f | %11.3f | %22.2f | %11.0f | %16.1f |\n", v.name, v.perFrame, 1 / v.perFrame,
                  v.cpu, kCores / v.cpu, v.bytes, v.bytes * 8 * 60 / 1e6);
    }
  }

  // 5. The film.
  std::printf("\n5. The 10-minute film: 36,000 frames at the rates measured above\n");
  std::printf("   (render is synthetic here; these are the export's own costs, which a renderer\n"
              "   faster than them hides completely and a slower one hides behind its own time; the\n"
              "   estimate divides the measured CPU time per frame by the 2 cores of an idle machine)\n");
  const double renderRef = 7.0 * 3600 / kFilm;
  std::printf("| pipeline                                   | export s/frame | idle 2-core est. | film, export alone (est.) | film with a %.2f s/frame render | vs 7 h + 15 h |\n",
              renderRef);
  std::printf("|--------------------------------------------|---------------:|-----------------:|--------------------------:|-------------------------------:|--------------:|\n");
  std::printf("| %-42s | %14s | %16s | %25s | %30s | %12.2fx |\n", "reference: game engine render, re-encode", "-", "-",
              "15h 00m (re-encode)", hms(kReferenceHours * 3600).c_str(), 1.0);
  auto row = [&](const std::string& name, double perFrame, double idlePerFrame) {
    // Writing overlaps rendering: the film takes the longer of the two.
    const double withRender = std::max(renderRef, idlePerFrame) * kFilm;
    std::printf("| %-42s | %14.3f | %16.3f | %25s | %30s | %12.2fx |\n", name.c_str(), perFrame, idlePerFrame,
                hms(idlePerFrame * kFilm).c_str(), hms(withRender).c_str(), kReferenceHours * 3600 / withRender);
  };
  for (size_t i = 0; i < exportFps2.size(); ++i)
    row(std::string("export, 2 writers: ") + formats[i].name, 1.0 / exportFps2[i], exportCpu[i] / kCores);
  for (const VideoRow& v : videos)
    if (v.perFrame > 0) row(std::string("direct video: ") + v.name, v.perFrame, v.cpu / kCores);
  std::printf("(%.2f s/frame is the reference's own render pace, 7 h / 36,000 frames; bench_export_render\n"
              "measures hybridscape's render. The stand-in render of table 3 gave %.3f s/frame measured.)\n",
              renderRef, export2);
  std::printf("\nload average at the end: %.2f\n", loadAverage());
  fs::remove_all(outDir);
  return 0;
}
