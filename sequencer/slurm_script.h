#pragma once
// Render-farm runs on Slurm: a job array whose task i renders chunk i of the
// frame range with `hybridscape-cli render ... --frames a-b`, and a final job,
// dependent on the whole array, that checks every frame with
// `hybridscape-cli farm verify` (frame_verify.h). Because an export resumes
// and a frame renders the same anywhere, a task that is preempted,
// requeued or run again simply finishes its chunk.
#include <cstdint>
#include <string>
#include <vector>

#include "sequencer/frame_range.h"
#include "sequencer/stereo_layout.h"

namespace hs::sequencer {

struct FarmJob {
  std::string scenePath;            // as the nodes see it (a shared file system)
  FrameList frames;
  int64_t chunkSize = 600;          // frames per array task (10 s of film at 60 fps)
  StereoLayout layout = StereoLayout::SideBySide;
  int eyeWidth = 1920;
  int eyeHeight = 1080;
  std::string outputPattern = "frames/f_%05d.png";
  std::string workDir;              // absolute; jobs run here (--chdir). "" = where sbatch runs. No '"' in it
  std::string cli = "hybridscape-cli";
  std::string jobName = "hybridscape";
  std::string partition;            // "" = the cluster's default
  int cpusPerTask = 2;
  std::string memory = "8G";        // per task
  std::string timeLimit = "04:00:00";
  int maxConcurrent = 0;            // array throttle (%N); 0 = no limit
  std::string logDir = "slurm-logs";  // relative to workDir
  std::vector<std::string> renderArgs;   // more `render` options (e.g. "--camera", "Drone")
  std::vector<std::string> sbatchLines;  // more #SBATCH options (e.g. "--gres=gpu:1")
};

struct FarmScripts {
  std::string renderScript;  // render.sbatch: the job array
  std::string verifyScript;  // verify.sbatch: the final check
  std::string submitScript;  // submit.sh: sbatch both, the second after the first
  std::vector<FrameList> chunks;
  std::vector<std::string> warnings;  // e.g. more tasks than Slurm's default MaxArraySize
};

// Single-quotes `s` for bash ('it'\''s').
std::string shellQuote(const std::string& s);

// The command line of array task `chunk` and of the final check.
std::vector<std::string> renderCommand(const FarmJob& job, const FrameList& chunk);
std::vector<std::string> verifyCommand(const FarmJob& job);
std::string joinCommand(const std::vector<std::string>& args);  // quoted for bash

// The scripts. Errors (no frames, a bad chunk size) come back in `error`
// and empty scripts.
FarmScripts makeSlurmScripts(const FarmJob& job, std::string& error);

// Writes render.sbatch, verify.sbatch and submit.sh (executable) into `dir`.
bool writeSlurmScripts(const FarmScripts& scripts, const std::string& dir, std::string& error);

}  // namespace hs::sequencer
