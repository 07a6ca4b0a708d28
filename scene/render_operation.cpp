#include "scene/render_operation.h"

#include <string>
#include <vector>

#include "sequencer/camera_cuts.h"
#include "sequencer/export_loop.h"

namespace hs::scene {
namespace {

const std::vector<std::string> kAntialiasing = {"none", "fxaa", "msaa4", "smaa"};  // Antialiasing's order

ParamDecl text(const char* key, const char* label, const char* help, const char* valueName) {
  return {.key = key, .option = key, .label = label, .type = ParamType::Text, .help = help, .valueName = valueName};
}

ParamDecl exportParam(const char* key) { return paramIn(sequencer::exportParamDecls(), key); }

// What one frame and a sequence both take.
std::vector<ParamDecl> frameParams() {
  ParamDecl size = exportParam("size_px");
  size.help = "image size (one frame), or the size of one eye (a sequence)";
  size.group.clear();
  return {size,
          text("camera", "Camera",
               "camera entity to render from (one frame: the first camera, or with none a view that frames the "
               "whole scene; a sequence: its camera cuts (`cut add`), else the first camera the timeline "
               "animates, else the first camera; a camera named here is used for every frame, cuts or not)",
               "NAME"),
          {.key = "aa", .option = "aa", .label = "Anti-aliasing", .type = ParamType::Choice, .choices = kAntialiasing,
           .help = "override the scene's anti-aliasing setting", .valueName = "A"},
          {.key = "no_grid", .option = "no-grid", .label = "No grid", .type = ParamType::Flag,
           .help = "hide the ground grid"},
          exportParam("quality")};
}

}  // namespace

Antialiasing antialiasingFromChoice(const std::string& name) {
  for (size_t i = 0; i < kAntialiasing.size(); ++i)
    if (kAntialiasing[i] == name) return Antialiasing(i);
  return Antialiasing::Msaa4;
}

const OperationDecl& renderOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{
        .name = "render",
        .summary = "render a frame or a stereo frame sequence headless (PNG, EXR, JPEG, TIFF, MP4)",
        .usage = "<scene.hscene> --out FILE [options]\n"
                 "       hybridscape-cli render <scene.hscene> --frames LIST --out PATTERN [options]",
        .description = "Renders one frame headless (EGL, no X server needed). The image type follows the "
                       "extension: .png, .jpg, .tif (8-bit sRGB) or .exr (linear half float).\n\n"
                       "A frame sequence: any of the sequence options; the scene's timeline plays, and the camera's "
                       "stereo rig gives the two eyes. --out is then a pattern: frames/f_%05d.png or f_#####.exr "
                       "(%v/%V: eye name).",
        .notes = "Progress and an ETA go to stderr. Ctrl-C stops after the frames in flight are written.",
        .positionals = {{.name = "scene.hscene", .help = "the scene file"}}};
    o.params = {text("out", "Output", "the image to write (a sequence: the frame files' pattern)", "FILE")};
    appendParams(o.params, frameParams());
    o.params.push_back(text("stats", "Statistics",
                            "write the frame's passes (CPU and GPU time, GPU memory each), GPU memory held, "
                            "triangles and draw calls as JSON (one frame, not a sequence)",
                            "FILE.json"));
    o.params.push_back({.key = "time_s", .option = "at", .label = "Time", .unit = Unit::Seconds, .min = 0.0,
                        .max = 1e7,
                        .help = "render the scene as its timeline has it at this time (one frame; the same pixels "
                                "as that frame of a sequence render, through the camera cuts' shot there unless "
                                "--camera names one). Without it: the document as it is, at t = 0",
                        .valueName = "SECONDS"});
    // Two shots in one frame (the renderer's view groups): a cross-fade still.
    o.params.push_back({.key = "mix_camera", .option = "mix-camera", .label = "Mix camera", .type = ParamType::Text,
                        .help = "a second camera rendered in the same frame (its own visible set, levels of detail, "
                                "shadows and lights) and mixed with the first by --mix (one frame)",
                        .valueName = "NAME"});
    o.params.push_back({.key = "mix", .option = "mix", .label = "Mix", .min = 0.0, .max = 1.0, .defaultValue = 0.5,
                        .help = "the second camera's share of the mixed frame (0: the first camera's image, 1: the "
                                "second's), summed in linear light before the tone map; with --transition, the "
                                "transition's progress",
                        .valueName = "0..1"});
    // A transition's frame as a still (docs/sequencer.md "Transitions").
    std::vector<std::string> kinds = sequencer::transitionNameList();
    std::erase(kinds, std::string("cut"));
    o.params.push_back({.key = "mix_transition", .option = "transition", .label = "Transition",
                        .type = ParamType::Choice, .defaultValue = "crossfade", .choices = kinds,
                        .help = "how --mix-camera's shot comes in: a transition drawn at progress --mix (the glitch "
                                "seeded by the frame at --at)",
                        .valueName = "KIND"});
    for (const ParamDecl& p : sequencer::exportParamDecls())
      if (p.key != "size_px" && p.key != "quality") o.params.push_back(p);
    return o;
  }();
  return op;
}

const OperationDecl& farmSlurmOperation() {
  static const OperationDecl op = [] {
    OperationDecl o{
        .name = "farm slurm",
        .summary = "write (--submit) a Slurm job array",
        .usage = "<scene.hscene> --out PATTERN [options]",
        .description = "Writes a Slurm job array that renders the frames in chunks (one array task each, running "
                       "`hybridscape-cli render --frames <chunk>`), a check that runs after the whole array and "
                       "lists missing or invalid frames, and submit.sh that submits both. Tasks resume: a requeued "
                       "or repeated task only renders what is missing.",
        .notes = "The scene, the output and the program are referred to by absolute path: the nodes must see this "
                 "file system. Afterwards: sbatch --array=<ids> render.sbatch re-runs chunks.",
        .positionals = {{.name = "scene.hscene", .help = "the scene file"}}};
    ParamDecl frames = exportParam("frames");
    frames.group.clear();
    ParamDecl layout = exportParam("layout");
    layout.group.clear();
    ParamDecl out = text("out", "Output", "frame files, e.g. frames/f_%05d.png (relative to here)", "PATTERN");
    out.required = true;
    o.params = {
        frames,
        {.key = "chunk", .option = "chunk", .label = "Chunk", .min = 1, .max = 100000000, .integer = true,
         .defaultValue = 600, .help = "frames per array task", .valueName = "N"},
        layout,
        out,
        text("dir", "Folder", "where the scripts go and the jobs run (default: here)", "DIR"),
        {.key = "submit", .option = "submit", .label = "Submit", .type = ParamType::Flag,
         .help = "submit with sbatch (prints the job ids)"},
        text("partition", "Partition", "Slurm partition", "P"),
        {.key = "max_running", .option = "max-running", .label = "Array throttle", .min = 0, .max = 1000000,
         .integer = true, .defaultValue = 0, .help = "array tasks running at once (0: no limit)", .valueName = "N"},
        text("time", "Time limit", "time limit per task (default 04:00:00)", "T"),
        text("mem", "Memory", "memory per task (default 8G)", "M"),
        {.key = "cpus", .option = "cpus", .label = "CPUs", .min = 1, .max = 4096, .integer = true, .defaultValue = 2,
         .help = "CPUs per task", .valueName = "N"},
        text("name", "Job name", "job name (default hybridscape)", "NAME"),
        text("sbatch", "sbatch option", "one more #SBATCH option, e.g. --gres=gpu:1", "LINE"),
    };
    // Passed on to every render task.
    for (ParamDecl p : frameParams()) {
      p.group = "passed on to every render task";
      o.params.push_back(p);
    }
    for (const char* key : {"fps", "png16"}) {
      ParamDecl p = exportParam(key);
      p.group = "passed on to every render task";
      o.params.push_back(p);
    }
    for (ParamDecl& p : o.params) p.editor = false;  // the editor writes no farm jobs
    return o;
  }();
  return op;
}

}  // namespace hs::scene
