// The sequencer's parameters as users set them, declared once
// (core/params.h): frame numbers, an export's settings, a camera path's aim
// and banking.
#include <cstdint>
#include <limits>

#include "core/world_extent.h"
#include "sequencer/camera_path.h"
#include "sequencer/comfort_check.h"
#include "sequencer/export_loop.h"
#include "sequencer/frame_range.h"

namespace hs::sequencer {

const ParamDecl& frameNumberDecl() {
  static const ParamDecl decl{.key = "frame", .label = "Frame", .min = 0,
                              .max = double(std::numeric_limits<int32_t>::max()), .integer = true,
                              .help = "a frame number", .valueName = "N"};
  return decl;
}

bool checkFrameBounds(const FrameList& frames, const std::string& name, std::string& error) {
  if (frames.empty()) return true;
  const ParamDecl& d = frameNumberDecl();
  for (const int64_t f : {frames.first(), frames.last()}) {
    std::string unused;
    if (!checkParam(d, Json(f), unused)) {
      error = name + ": frame " + std::to_string(f) + " is out of range (" + rangeText(d) + ")";
      return false;
    }
  }
  return true;
}

const std::vector<ParamDecl>& exportParamDecls() {
  static const std::vector<ParamDecl> decls = [] {
    const ExportSettings d;
    const ComfortBudget budget;
    // Every layout by its name, with the other names it is known by.
    std::vector<std::string> layouts = {
        std::string(layoutName(StereoLayout::SideBySide)) + "|sbs-full|side-by-side",
        std::string(layoutName(StereoLayout::SideBySideSqueezed)) + "|sbs-squeezed|half-sbs",
        std::string(layoutName(StereoLayout::TopBottom)) + "|top-bottom|tab",
        std::string(layoutName(StereoLayout::TopBottomSqueezed)) + "|tb-squeezed|half-tab",
        std::string(layoutName(StereoLayout::Separate)) + "|left-right",
        layoutName(StereoLayout::Anaglyph),
        layoutName(StereoLayout::Mono)};
    const std::string seq = "sequence";
    return std::vector<ParamDecl>{
        {.key = "frames", .option = "frames", .label = "Frames", .type = ParamType::Text,
         .help = "frames to render: 0-35999, 10,20-30, 0-100x10 (default: the scene's range)", .valueName = "LIST",
         .group = seq},
        {.key = "layout", .option = "layout", .label = "Layout", .type = ParamType::Choice,
         .defaultValue = layoutName(d.layout), .choices = layouts,
         .help = "sbs: 2W x H; sbs-half / tb-half squeezed into one eye's size; separate: two files a frame; "
                 "anaglyph: red/cyan; mono: the camera only",
         .valueName = "L", .editor = true, .group = seq},
        {.key = "size_px", .option = "size", .label = "Size", .unit = Unit::Pixels, .min = 1, .max = 16384,
         .integer = true, .defaultValue = Json::array({d.eyeWidth, d.eyeHeight}), .help = "size of one eye",
         .valueName = "WxH", .count = 2, .separator = 'x', .editor = true, .group = seq},
        {.key = "fps", .option = "fps", .label = "Frame rate", .type = ParamType::Text,
         .help = "override the scene's frame rate (60, 59.94, 60000/1001)", .valueName = "RATE", .group = seq},
        {.key = "quality", .option = "quality", .label = "Quality", .min = 1, .max = 100, .integer = true,
         .defaultValue = d.image.jpegQuality, .help = "JPEG quality", .valueName = "N", .editor = true},
        {.key = "png16", .option = "png16", .label = "16-bit PNG", .type = ParamType::Flag, .help = "16-bit PNG",
         .group = seq},
        {.key = "video", .option = "video", .label = "Film", .type = ParamType::Text,
         .help = "a film instead of images: .mp4 or .mkv, H.264/H.265 through ffmpeg, with side-by-side / "
                 "top-bottom stereo metadata (not resumable)",
         .valueName = "FILE", .group = seq},
        {.key = "codec", .option = "codec", .label = "Codec", .type = ParamType::Choice, .defaultValue = "h264",
         .choices = {"h264", "h265|hevc"}, .help = "the film's codec", .valueName = "C", .group = seq},
        {.key = "crf", .option = "crf", .label = "Quality (CRF)", .min = 0, .max = 51, .integer = true,
         .defaultValue = d.video.crf,
         .help = "x264/x265 constant rate factor: lower is better and larger (18 is visually lossless)",
         .valueName = "N", .editor = true, .group = seq},
        {.key = "preset", .option = "preset", .label = "Preset", .type = ParamType::Text,
         .defaultValue = d.video.preset, .help = "x264/x265 speed preset", .valueName = "P", .group = seq},
        {.key = "comfort", .option = "comfort", .label = "Comfort check", .type = ParamType::Flag,
         .help = "print each frame's nearest and farthest screen parallax (share of the width) and flag frames "
                 "outside the budget",
         .group = seq},
        {.key = "budget_pct", .option = "budget", .label = "Comfort budget", .unit = Unit::Percent, .min = -100.0,
         .max = 100.0, .defaultValue = Json::array({budget.nearest * 100.0, budget.farthest * 100.0}),
         .help = "the comfort budget NEAR,FAR in percent of the width: the most negative (in front of the screen) "
                 "and the most positive parallax allowed",
         .valueName = "N,F", .count = 2, .group = seq, .componentRanges = {{-100.0, 0.0}, {0.0, 100.0}}},
        {.key = "overwrite", .option = "overwrite", .label = "Overwrite", .type = ParamType::Flag,
         .help = "render every frame again (default: valid frames of an earlier run are kept and only the rest is "
                 "rendered, so an interrupted run resumes)",
         .group = seq},
        {.key = "writers", .option = "writers", .label = "Writers", .min = 1, .max = 64, .integer = true,
         .defaultValue = d.writerThreads, .help = "encoder threads", .valueName = "N", .group = seq},
    };
  }();
  return decls;
}

const std::vector<ParamDecl>& pathFollowParamDecls() {
  static const std::vector<ParamDecl> decls = [] {
    const PathFollow d;
    return std::vector<ParamDecl>{
        {.key = "look_at_m", .option = "look-at", .label = "Target", .unit = Unit::Metres,
         .min = -kWorldExtentMetres, .max = kWorldExtentMetres, .help = "aim at a point", .valueName = "X,Y,Z",
         .count = 3},
        {.key = "bank_deg", .option = "bank", .label = "Limit", .unit = Unit::Degrees, .min = 0.0, .max = 90.0,
         .defaultValue = d.maxBankDeg,
         .help = "bank into turns like an aircraft, at most this many degrees (0 turns banking off)",
         .valueName = "MAXDEG", .editor = true, .decimals = 2},
        {.key = "bank_scale", .option = "bank-scale", .label = "Strength", .min = 0.01, .max = 20.0,
         .defaultValue = d.bankScale, .help = "banking strength: 1 is a coordinated turn, less is gentler",
         .valueName = "K", .editor = true, .decimals = 2, .step = 0.1},
    };
  }();
  return decls;
}

}  // namespace hs::sequencer
