// hs_sequencer_tool: the command-line surface phase 2 gives hybridscape-cli,
// with a synthetic renderer, for trying generated Slurm scripts on a real
// Slurm before render/ is wired in and for killing a real export process
// in tests. Not installed; the scene argument is accepted and ignored.
//
//   hs_sequencer_tool render SCENE --frames 0-99 --layout sbs --size 64x32 --out dir/f_%05d.png
//                     [--slow MS] [--threads N] [--no-resume] [--tag TAG]
//   hs_sequencer_tool farm verify --frames 0-99 --layout sbs --size 64x32 --out dir/f_%05d.png
//                     [--chunk N] [--deep] [--tag TAG]
//   hs_sequencer_tool farm slurm SCENE --frames 0-99 --chunk 25 --layout sbs --size 64x32
//                     --out dir/f_%05d.png --dir SCRIPTS --workdir DIR   (the CLI is this tool)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <thread>

#include "sequencer/export_loop.h"
#include "sequencer/frame_verify.h"
#include "sequencer/slurm_script.h"
#include "synthetic_frames.h"

using namespace hs::sequencer;

namespace {

int usage(const char* why) {
  std::fprintf(stderr, "hs_sequencer_tool: %s\n", why);
  return 2;
}

bool parseSize(const std::string& s, int& w, int& h) {
  return std::sscanf(s.c_str(), "%dx%d", &w, &h) == 2 && w > 0 && h > 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage("expected: render SCENE ... | farm verify ...");
  const std::string cmd = argv[1];
  int first = 2;
  if (cmd == "render") first = 3;  // skip the scene
  else if (cmd == "farm" && argc > 2 && std::strcmp(argv[2], "verify") == 0) first = 3;
  else if (cmd == "farm" && argc > 3 && std::strcmp(argv[2], "slurm") == 0) first = 4;
  else return usage("unknown command");
  std::map<std::string, std::string> opt;
  for (int i = first; i < argc; ++i) {
    std::string a = argv[i];
    if (a.rfind("--", 0) != 0) return usage(("unexpected argument " + a).c_str());
    a = a.substr(2);
    if (a == "deep" || a == "no-resume") opt[a] = "1";
    else if (i + 1 < argc) opt[a] = argv[++i];
    else return usage(("--" + a + " needs a value").c_str());
  }
  std::string error;
  const auto frames = FrameList::parse(opt["frames"], error);
  if (!frames) return usage(error.c_str());
  const auto layout = layoutFromName(opt.count("layout") ? opt["layout"] : "sbs");
  if (!layout) return usage("unknown layout");
  int w = 1920, h = 1080;
  if (opt.count("size") && !parseSize(opt["size"], w, h)) return usage("--size WxH");
  if (!opt.count("out")) return usage("--out PATTERN is required");

  if (cmd == "render") {
    ExportSettings s;
    s.frames = *frames;
    s.output = opt["out"];
    s.layout = *layout;
    s.eyeWidth = w;
    s.eyeHeight = h;
    s.resume = !opt.count("no-resume");
    s.jobTag = opt["tag"];
    if (opt.count("threads")) s.writerThreads = std::atoi(opt["threads"].c_str());
    const int slowMs = opt.count("slow") ? std::atoi(opt["slow"].c_str()) : 0;
    auto source = makeCallbackSource([slowMs](const FrameJob& job, EyeImages& out, std::string& err) {
      if (slowMs > 0) std::this_thread::sleep_for(std::chrono::milliseconds(slowMs));
      return hs::test::syntheticRender(job, out, err);
    });
    ExportCallbacks cb;
    cb.progress = [](const ExportProgress& p) {
      std::fprintf(stderr, "\r%lld/%lld frames, %.1f fps, eta %.0f s   ", static_cast<long long>(p.written + p.kept),
                   static_cast<long long>(p.total), p.framesPerSecond, p.etaSeconds);
    };
    const ExportResult r = runExport(s, *source, cb);
    std::fprintf(stderr, "\n");
    for (const std::string& n : r.notes) std::printf("%s\n", n.c_str());
    if (!r.ok) {
      std::fprintf(stderr, "hs_sequencer_tool render: %s\n", r.error.c_str());
      return 1;
    }
    std::printf("rendered %lld, kept %lld of %lld frames in %.2f s\n", static_cast<long long>(r.rendered),
                static_cast<long long>(r.kept), static_cast<long long>(r.total), r.seconds);
    return 0;
  }
  if (std::strcmp(argv[2], "slurm") == 0) {
    FarmJob job;
    job.scenePath = argv[3];
    job.frames = *frames;
    job.layout = *layout;
    job.eyeWidth = w;
    job.eyeHeight = h;
    job.outputPattern = opt["out"];
    job.workDir = opt["workdir"];
    job.cli = std::filesystem::canonical("/proc/self/exe").string();
    if (opt.count("chunk")) job.chunkSize = std::atoll(opt["chunk"].c_str());
    const FarmScripts scripts = makeSlurmScripts(job, error);
    if (!error.empty() || !writeSlurmScripts(scripts, opt["dir"], error)) return usage(error.c_str());
    for (const std::string& warning : scripts.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
    std::printf("wrote %s/render.sbatch (%zu tasks), verify.sbatch, submit.sh\n", opt["dir"].c_str(), scripts.chunks.size());
    return 0;
  }
  VerifySettings v;
  v.frames = *frames;
  v.outputPattern = opt["out"];
  v.layout = *layout;
  v.eyeWidth = w;
  v.eyeHeight = h;
  v.deep = opt.count("deep") > 0;
  v.jobTag = opt["tag"];
  if (opt.count("chunk")) v.chunkSize = std::atoll(opt["chunk"].c_str());
  const VerifyReport r = verifyFrames(v);
  std::printf("%s", r.summary().c_str());
  return r.complete() ? 0 : 1;
}
