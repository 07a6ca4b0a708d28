// `hybridscape-cli farm slurm|verify`: render-farm runs. `slurm` writes a
// Slurm job array whose tasks each run `hybridscape-cli render --frames
// <chunk>` (resumable, so a requeued task finishes its chunk) plus a check
// that waits for the whole array; `verify` is that check.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sys/wait.h>

#include "cli/cli_args.h"
#include "cli/commands.h"
#include "cli/sequence_options.h"
#include "scene/hscene_file.h"
#include "sequencer/ffmpeg_writer.h"
#include "sequencer/frame_verify.h"
#include "sequencer/image_writer.h"
#include "sequencer/output_pattern.h"
#include "sequencer/slurm_script.h"

namespace hs::cli {

namespace fs = std::filesystem;

namespace {

// The path of this program, so the array tasks run the same build (the
// nodes share the file system the scene is on).
std::string selfPath() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("hybridscape-cli") : p.string();
}

std::string absolute(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::absolute(path, ec);
  return ec ? path : p.lexically_normal().string();
}

// Runs a command line through bash, capturing its output; returns its status.
int runCapture(const std::string& command, std::string& output) {
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  if (!p) return -1;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) output.append(buf, n);
  const int status = pclose(p);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string lastLine(const std::string& text) {
  std::string t = text;
  while (!t.empty() && (t.back() == '\n' || t.back() == '\r')) t.pop_back();
  const size_t nl = t.rfind('\n');
  return nl == std::string::npos ? t : t.substr(nl + 1);
}

int runSlurm(int argc, char** argv) {
  const char* cmd = "farm slurm";
  Args args;
  std::string error;
  if (!parseArgs(argc, argv, 0,
                 {{"frames"}, {"chunk"}, {"layout"}, {"size"}, {"out"}, {"submit", false}, {"partition"}, {"dir"},
                  {"camera"}, {"fps"}, {"quality"}, {"png16", false}, {"no-grid", false}, {"aa"}, {"max-running"},
                  {"time"}, {"mem"}, {"cpus"}, {"name"}, {"sbatch"}},
                 args, error))
    return usage(cmd, error);
  if (args.help) {
    std::printf(
        "usage: hybridscape-cli farm slurm <scene.hscene> --out PATTERN [options]\n\n"
        "Writes a Slurm job array that renders the frames in chunks (one array task each,\n"
        "running `hybridscape-cli render --frames <chunk>`), a check that runs after the\n"
        "whole array and lists missing or invalid frames, and submit.sh that submits both.\n"
        "Tasks resume: a requeued or repeated task only renders what is missing.\n\n"
        "  --frames LIST    frames (default: the scene's range), e.g. 0-35999\n"
        "  --chunk N        frames per array task (default 600)\n"
        "  --layout L       sbs, sbs-squeezed, tb, tb-squeezed, separate, anaglyph, mono (default sbs)\n"
        "  --size WxH       size of one eye (default 1920x1080)\n"
        "  --out PATTERN    frame files, e.g. frames/f_%%05d.png (relative to here)\n"
        "  --dir DIR        where the scripts go and the jobs run (default: here)\n"
        "  --submit         submit with sbatch (prints the job ids)\n"
        "  --partition P    Slurm partition;  --max-running N  array throttle\n"
        "  --time T         time limit per task (default 04:00:00);  --mem M (default 8G);  --cpus N (default 2)\n"
        "  --name NAME      job name (default hybridscape)\n"
        "  --sbatch LINE    one more #SBATCH option, e.g. --gres=gpu:1\n"
        "  --camera, --fps, --quality, --png16, --no-grid, --aa   passed on to every render task\n\n"
        "The scene, the output and the program are referred to by absolute path: the nodes must\n"
        "see this file system. Afterwards: sbatch --array=<ids> render.sbatch re-runs chunks.\n");
    return 0;
  }
  if (args.positional.size() != 1) return usage(cmd, "expected one scene file");
  const std::string scenePath = args.positional[0];
  const auto out = args.get("out");
  if (!out) return usage(cmd, "--out PATTERN is required (for example frames/f_%05d.png)");
  if (sequencer::videoContainerFromPath(*out))
    return usage(cmd, "a farm renders image sequences (chunks on many machines); encode the film from the frames "
                      "afterwards, or use `render --video` on one machine");
  sequencer::FarmJob job;
  if (!parseLayout(args, job.layout, error) || !parseEyeSize(args, job.eyeWidth, job.eyeHeight, error))
    return usage(cmd, error);
  int chunk = 600, maxRunning = 0, cpus = 2;
  if (!parseIntOption(args, "chunk", 1, 100000000, chunk, error) ||
      !parseIntOption(args, "max-running", 0, 1000000, maxRunning, error) ||
      !parseIntOption(args, "cpus", 1, 4096, cpus, error))
    return usage(cmd, error);
  std::optional<scene::SceneState> state = scene::loadScene(scenePath, error);
  if (!state) return fail(cmd, error);
  if (!parseFrames(args, &*state, job.frames, error)) return usage(cmd, error);
  // Refuse now what every task would refuse later.
  if (findCamera(*state, args.get("camera").value_or(""), scenePath, error) == scene::kNoEntity)
    return fail(cmd, error);
  if (auto fps = args.get("fps"); fps && !sequencer::parseFrameRate(*fps, error)) return usage(cmd, "--fps: " + error);
  if (!sequencer::OutputPattern::parse(*out, error)) return usage(cmd, "--out: " + error);
  if (!sequencer::imageFormatFromPath(*out)) return fail(cmd, *out + ": unknown image type; use .png, .exr, .jpg, .tif");

  const std::string dir = absolute(args.get("dir").value_or("."));
  job.scenePath = absolute(scenePath);
  job.outputPattern = absolute(*out);
  job.chunkSize = chunk;
  job.workDir = dir;
  job.cli = selfPath();
  job.maxConcurrent = maxRunning;
  job.cpusPerTask = cpus;
  if (auto p = args.get("partition")) job.partition = *p;
  if (auto t = args.get("time")) job.timeLimit = *t;
  if (auto m = args.get("mem")) job.memory = *m;
  if (auto n = args.get("name")) job.jobName = *n;
  if (auto l = args.get("sbatch")) job.sbatchLines.push_back(*l);
  for (const char* name : {"camera", "fps", "quality", "aa"})
    if (auto v = args.get(name)) job.renderArgs.insert(job.renderArgs.end(), {std::string("--") + name, *v});
  for (const char* flag : {"png16", "no-grid"})
    if (args.has(flag)) job.renderArgs.push_back(std::string("--") + flag);
  if (dir.find('"') != std::string::npos) return fail(cmd, "--dir " + dir + ": a folder name with '\"' cannot be a Slurm --chdir");

  const sequencer::FarmScripts scripts = sequencer::makeSlurmScripts(job, error);
  if (!error.empty()) return fail(cmd, error);
  if (!sequencer::writeSlurmScripts(scripts, dir, error)) return fail(cmd, error);
  for (const std::string& w : scripts.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  std::printf("wrote %s/render.sbatch (%zu array task(s) of up to %d frames, %lld frames), verify.sbatch and "
              "submit.sh\n",
              dir.c_str(), scripts.chunks.size(), chunk, static_cast<long long>(job.frames.count()));
  if (!args.has("submit")) {
    std::printf("submit with: %s/submit.sh\n", dir.c_str());
    return 0;
  }
  std::string output;
  if (runCapture("command -v sbatch >/dev/null", output) != 0)
    return fail(cmd, "--submit: sbatch is not on PATH (is Slurm installed on this machine?); the scripts are in " + dir);
  output.clear();
  const int status = runCapture(sequencer::shellQuote(dir + "/submit.sh"), output);
  if (status != 0) return fail(cmd, "--submit: sbatch failed: " + lastLine(output));
  std::printf("%s", output.c_str());
  return 0;
}

int runVerify(int argc, char** argv) {
  const char* cmd = "farm verify";
  Args args;
  std::string error;
  if (!parseArgs(argc, argv, 0,
                 {{"frames"}, {"out"}, {"size"}, {"layout"}, {"chunk"}, {"deep", false}, {"tag"}, {"threads"}}, args,
                 error))
    return usage(cmd, error);
  if (args.help) {
    std::printf(
        "usage: hybridscape-cli farm verify --frames LIST --out PATTERN [--size WxH] [--layout L] [options]\n\n"
        "Checks that every frame of the list exists and is a valid image of the layout's size\n"
        "(the check a farm run ends with). Exit 0 when all are there; 1 with the missing and\n"
        "invalid frames listed (and, with --chunk, the array tasks to run again).\n\n"
        "  --size WxH       size of one eye (default 1920x1080)\n"
        "  --layout L       as for render (default sbs)\n"
        "  --chunk N        the farm's chunk size: name the chunks to run again\n"
        "  --deep           decode every pixel (finds damaged files; slower)\n"
        "  --tag TAG        also require the export's job tag in each file\n"
        "  --threads N      files checked in parallel (default 2)\n");
    return 0;
  }
  if (!args.positional.empty()) return usage(cmd, "unexpected argument '" + args.positional[0] + "'");
  sequencer::VerifySettings v;
  if (!parseFrames(args, nullptr, v.frames, error) || !parseLayout(args, v.layout, error) ||
      !parseEyeSize(args, v.eyeWidth, v.eyeHeight, error))
    return usage(cmd, error);
  const auto out = args.get("out");
  if (!out) return usage(cmd, "--out PATTERN is required");
  v.outputPattern = *out;
  int chunk = 0, threads = 2;
  if (!parseIntOption(args, "chunk", 0, 100000000, chunk, error) ||
      !parseIntOption(args, "threads", 1, 256, threads, error))
    return usage(cmd, error);
  v.chunkSize = chunk;
  v.threads = threads;
  v.deep = args.has("deep");
  v.jobTag = args.get("tag").value_or("");
  const sequencer::VerifyReport r = sequencer::verifyFrames(v);
  if (!r.error.empty()) return fail(cmd, r.error);
  if (r.complete()) {
    std::printf("%s", r.summary().c_str());
    return 0;
  }
  // The report for a person on stdout; the one-line reason on stderr.
  std::printf("%s", r.summary().c_str());
  return fail(cmd, std::to_string(r.missing.size()) + " frame(s) missing and " + std::to_string(r.invalid.size()) +
                       " invalid of " + std::to_string(r.expectedFrames) +
                       (r.missing.empty() ? std::string() : " (missing: " +
                            sequencer::FrameList::fromFrames(r.missing).toString() + ")"));
}

}  // namespace

int runFarm(int argc, char** argv) {
  if (argc >= 1 && !std::strcmp(argv[0], "slurm")) return runSlurm(argc - 1, argv + 1);
  if (argc >= 1 && !std::strcmp(argv[0], "verify")) return runVerify(argc - 1, argv + 1);
  if (argc >= 1 && (!std::strcmp(argv[0], "--help") || !std::strcmp(argv[0], "-h"))) {
    std::printf(
        "usage: hybridscape-cli farm slurm <scene.hscene> --out PATTERN [options]   write (--submit) a Slurm job array\n"
        "       hybridscape-cli farm verify --frames LIST --out PATTERN [options]   check a finished run\n"
        "(see hybridscape-cli farm slurm --help, farm verify --help)\n");
    return 0;
  }
  return usage("farm", argc >= 1 ? "unknown farm command '" + std::string(argv[0]) + "' (slurm or verify)"
                                  : std::string("expected slurm or verify"));
}

}  // namespace hs::cli
