// `hybridscape-cli farm slurm|verify`: render-farm runs. `slurm` writes a
// Slurm job array whose tasks each run `hybridscape-cli render --frames
// <chunk>` (resumable, so a requeued task finishes its chunk) plus a check
// that waits for the whole array; `verify` is that check.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sys/wait.h>

#include "cli/commands.h"
#include "cli/operation_options.h"
#include "cli/scene_open.h"
#include "cli/sequence_options.h"
#include "scene/hscene_file.h"
#include "scene/render_operation.h"
#include "sequencer/ffmpeg_writer.h"
#include "sequencer/frame_verify.h"
#include "sequencer/image_writer.h"
#include "sequencer/output_pattern.h"
#include "sequencer/sequencer_operations.h"
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
  OperationArgs args(scene::farmSlurmOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (args.positionals().size() != 1) return args.usage("expected one scene file");
  const std::string scenePath = args.positionals()[0];
  const std::string out = args.text("out");
  if (sequencer::videoContainerFromPath(out))
    return args.usage("a farm renders image sequences (chunks on many machines); encode the film from the frames "
                      "afterwards, or use `render --video` on one machine");
  sequencer::FarmJob job;
  job.layout = layoutOf(args);
  eyeSizeOf(args, job.eyeWidth, job.eyeHeight);
  const int chunk = int(args.integer("chunk"));
  std::string error;
  std::optional<scene::SceneState> state = openScene(scenePath, error);
  if (!state) return args.fail(error);
  if (!parseFrames(args, &*state, job.frames, error)) return args.usage(error);
  // Refuse now what every task would refuse later.
  if (findCamera(*state, args.text("camera"), scenePath, error) == scene::kNoEntity) return args.fail(error);
  if (args.has("fps") && !sequencer::parseFrameRate(args.text("fps"), error)) return args.usage("--fps: " + error);
  if (!sequencer::OutputPattern::parse(out, error)) return args.usage("--out: " + error);
  if (!sequencer::imageFormatFromPath(out)) return args.fail(out + ": unknown image type; use .png, .exr, .jpg, .tif");

  const std::string dir = absolute(args.has("dir") ? args.text("dir") : std::string("."));
  job.scenePath = absolute(scenePath);
  job.outputPattern = absolute(out);
  job.chunkSize = chunk;
  job.workDir = dir;
  job.cli = selfPath();
  job.maxConcurrent = int(args.integer("max_running"));
  job.cpusPerTask = int(args.integer("cpus"));
  if (args.has("partition")) job.partition = args.text("partition");
  if (args.has("time")) job.timeLimit = args.text("time");
  if (args.has("mem")) job.memory = args.text("mem");
  if (args.has("name")) job.jobName = args.text("name");
  if (args.has("sbatch")) job.sbatchLines.push_back(args.text("sbatch"));
  // What the array tasks' `render` takes, as it was given here.
  for (const char* key : {"camera", "fps", "quality", "aa"})
    if (args.has(key))
      job.renderArgs.insert(job.renderArgs.end(),
                            {"--" + scene::farmSlurmOperation().param(key).option, *args.given(key)});
  for (const char* key : {"png16", "no_grid"})
    if (args.flag(key)) job.renderArgs.push_back("--" + scene::farmSlurmOperation().param(key).option);
  if (dir.find('"') != std::string::npos)
    return args.fail("--dir " + dir + ": a folder name with '\"' cannot be a Slurm --chdir");

  const sequencer::FarmScripts scripts = sequencer::makeSlurmScripts(job, error);
  if (!error.empty()) return args.fail(error);
  if (!sequencer::writeSlurmScripts(scripts, dir, error)) return args.fail(error);
  for (const std::string& w : scripts.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  std::printf("wrote %s/render.sbatch (%zu array task(s) of up to %d frames, %lld frames), verify.sbatch and "
              "submit.sh\n",
              dir.c_str(), scripts.chunks.size(), chunk, static_cast<long long>(job.frames.count()));
  if (!args.flag("submit")) {
    std::printf("submit with: %s/submit.sh\n", dir.c_str());
    return 0;
  }
  std::string output;
  if (runCapture("command -v sbatch >/dev/null", output) != 0)
    return args.fail("--submit: sbatch is not on PATH (is Slurm installed on this machine?); the scripts are in " + dir);
  output.clear();
  const int status = runCapture(sequencer::shellQuote(dir + "/submit.sh"), output);
  if (status != 0) return args.fail("--submit: sbatch failed: " + lastLine(output));
  std::printf("%s", output.c_str());
  return 0;
}

int runVerify(int argc, char** argv) {
  OperationArgs args(sequencer::farmVerifyOperation());
  if (auto code = args.parse(argc, argv)) return *code;
  if (!args.positionals().empty()) return args.usage("unexpected argument '" + args.positionals()[0] + "'");
  sequencer::VerifySettings v;
  std::string error;
  if (!parseFrames(args, nullptr, v.frames, error)) return args.usage(error);
  v.layout = layoutOf(args);
  eyeSizeOf(args, v.eyeWidth, v.eyeHeight);
  v.outputPattern = args.text("out");
  v.chunkSize = args.integer("chunk");
  v.threads = int(args.integer("threads"));
  v.deep = args.flag("deep");
  v.jobTag = args.text("tag");
  const sequencer::VerifyReport r = sequencer::verifyFrames(v);
  if (!r.error.empty()) return args.fail(r.error);
  if (r.complete()) {
    std::printf("%s", r.summary().c_str());
    return 0;
  }
  // The report for a person on stdout; the one-line reason on stderr.
  std::printf("%s", r.summary().c_str());
  return args.fail(std::to_string(r.missing.size()) + " frame(s) missing and " + std::to_string(r.invalid.size()) +
                       " invalid of " + std::to_string(r.expectedFrames) +
                       (r.missing.empty() ? std::string() : " (missing: " +
                            sequencer::FrameList::fromFrames(r.missing).toString() + ")"));
}

}  // namespace

int runFarm(int argc, char** argv) {
  if (argc >= 1 && !std::strcmp(argv[0], "slurm")) return runSlurm(argc - 1, argv + 1);
  if (argc >= 1 && !std::strcmp(argv[0], "verify")) return runVerify(argc - 1, argv + 1);
  if (argc >= 1 && (!std::strcmp(argv[0], "--help") || !std::strcmp(argv[0], "-h"))) {
    std::printf("usage: hybridscape-cli farm slurm %s\n       hybridscape-cli farm verify %s\n\n",
                scene::farmSlurmOperation().usage.c_str(), sequencer::farmVerifyOperation().usage.c_str());
    for (const OperationDecl* op : {&scene::farmSlurmOperation(), &sequencer::farmVerifyOperation()})
      std::printf("  %-14s %s\n", op->name.c_str(), op->summary.c_str());
    std::printf("\n(see hybridscape-cli farm slurm --help, farm verify --help)\n");
    return 0;
  }
  return usageCommand("farm", argc >= 1 ? "unknown farm command '" + std::string(argv[0]) + "' (slurm or verify)"
                                         : std::string("expected slurm or verify"));
}

}  // namespace hs::cli
