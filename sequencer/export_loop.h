#pragma once
// The frame export loop: renders each frame through a caller-supplied
// source (render::StereoFrameSource: GL and pixel buffers; tests use
// synthetic sources), and composes, encodes
// and writes on writer threads behind a bounded queue, so writing overlaps
// rendering and an export costs little more than its rendering.
//
// Guarantees (docs/sequencer.md):
// - A frame file is complete or absent (write-then-rename).
// - Resume: frames whose files are valid (OpenImageIO reads a header of the
//   right size, and with a job tag, the same tag) are kept; stray temporary
//   files of this export's frames (a killed run) are removed; the rest is
//   rendered. A frame renders the same in any run (the sequence is a pure
//   function of t), so a resumed or split export is byte-identical to one run.
// - The first failure (render or write: full disk, read-only folder) stops
//   the export with an error naming the frame and the file; every frame
//   finished before it stays on disk.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/params.h"
#include "core/progress.h"
#include "sequencer/ffmpeg_writer.h"
#include "sequencer/frame_range.h"
#include "sequencer/image_writer.h"
#include "sequencer/stereo_layout.h"

namespace hs::sequencer {

// One frame to render: what the renderer is asked for.
struct FrameJob {
  int64_t frame = 0;
  double time = 0.0;        // frameTime(frame, rate): evaluate the sequence here
  int64_t index = 0;        // position among the frames this run renders, from 0
  int eyeWidth = 1920;
  int eyeHeight = 1080;
  bool bothEyes = true;     // false (mono layout): render the mono camera into `left`
  bool floatPixels = false; // EXR output wants linear float pixels
};

struct EyeImages {
  Image left;
  Image right;
};

// The renderer side. begin() starts a frame and may return before its
// pixels are read back (GPU work and an asynchronous readback continue);
// finish() hands over the pixels of the oldest begun frame. The loop keeps
// framesInFlight() frames begun, so with 2 the renderer draws frame N+1
// while frame N's pixel buffers are mapped. All calls come from the thread
// that called runExport() (the one with the GL context).
class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual bool begin(const FrameJob& job, std::string& error) = 0;
  virtual bool finish(const FrameJob& job, EyeImages& out, std::string& error) = 0;
  virtual int framesInFlight() const { return 1; }
};

// A plain synchronous render callback as a FrameSource.
using RenderFn = std::function<bool(const FrameJob& job, EyeImages& out, std::string& error)>;
std::unique_ptr<FrameSource> makeCallbackSource(RenderFn render);

struct ExportSettings {
  FrameList frames;
  FrameRate rate{60, 1};
  // An image pattern ("frames/f_%05d.png": PNG, EXR, JPEG or TIFF by
  // extension) or a film (".mp4", ".mkv": through ffmpeg).
  std::string output;
  StereoLayout layout = StereoLayout::SideBySide;
  AnaglyphMethod anaglyph = AnaglyphMethod::Dubois;
  int eyeWidth = 1920;
  int eyeHeight = 1080;
  WriteOptions image;    // JPEG quality, 16-bit PNG, fsync (description comes from jobTag)
  VideoSettings video;   // codec, crf, preset (size, rate and layout are taken from here)
  int writerThreads = 2;
  int queueDepth = 0;    // frames waiting for a writer; 0 = writerThreads + 1
  bool resume = true;    // false: render and overwrite every frame
  // Identifies the settings that made the frames (render::exportJobTag: a
  // hash of the scene content and render settings). Written into each
  // image's description; resume keeps only frames with the same tag. "" =
  // size only.
  std::string jobTag;
};

// ExportSettings' parameters as `render --frames` and the Export dialog
// set them, declared once: frames, layout, size_px (one eye), fps,
// quality, png16, video, codec, crf, preset, comfort, budget_pct,
// overwrite, writers.
const std::vector<ParamDecl>& exportParamDecls();

struct ExportProgress {
  int64_t total = 0;      // frames in the range
  int64_t kept = 0;       // valid from an earlier run
  int64_t rendered = 0;
  int64_t written = 0;    // finished this run
  double elapsedSeconds = 0.0;
  double framesPerSecond = 0.0;  // over the last frames (a window of 60 frames)
  double etaSeconds = -1.0;      // -1 until a frame is written
  int64_t lastFrame = -1;        // the frame most recently written
};

struct ExportResult {
  bool ok = false;
  bool cancelled = false;
  std::string error;                 // "frame 123: frames/f_00123.png: cannot write: disk full in frames (...)"
  std::optional<int64_t> failedFrame;
  int64_t total = 0;
  int64_t kept = 0;                  // valid frames kept from before
  int64_t replaced = 0;              // invalid frames found and rendered again
  int64_t removedTemporaries = 0;    // stray temporary files of a killed run
  int64_t rendered = 0;
  int64_t written = 0;
  double seconds = 0.0;              // wall time of the whole export
  double renderSeconds = 0.0;        // time inside the frame source (caller's thread)
  double writeSeconds = 0.0;         // time composing, encoding and writing (all writer threads)
  double waitSeconds = 0.0;          // caller's thread blocked on a full queue (writers are the bottleneck)
  std::vector<std::string> notes;
};

// Writes one output image (injectable: tests simulate failing disks).
using ImageSink = std::function<bool(const std::string& path, const Image& image, std::string& error)>;

struct ExportCallbacks {
  // Cancel (the export stops after the frames already rendered are
  // written) and the share of frames finished.
  const Progress* progress = nullptr;
  // Frame counts, speed and ETA: on the caller's thread, after each frame
  // and while draining.
  std::function<void(const ExportProgress&)> onFrame;
  ImageSink sink;  // default: encode and write atomically
};

// What a resumed export would do: the frames to render, after making the
// output folders and removing stray temporaries (neither when dryRun).
struct ResumePlan {
  std::vector<int64_t> toRender;
  int64_t kept = 0;
  int64_t invalid = 0;
  std::vector<std::string> invalidWhy;  // the first problems of invalid frames ("frame 3: f_003.png: damaged (...)")
  int64_t removedTemporaries = 0;
  std::string error;  // a bad pattern or settings
};
ResumePlan planExport(const ExportSettings& settings, bool dryRun = false);

ExportResult runExport(const ExportSettings& settings, FrameSource& source, const ExportCallbacks& callbacks = {});

}  // namespace hs::sequencer
