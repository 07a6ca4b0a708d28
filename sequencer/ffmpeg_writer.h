#pragma once
// Direct video output through Debian's ffmpeg: raw RGBA frames are piped to
// an ffmpeg process that encodes H.264 (libx264) or H.265 (libx265) into
// MP4 or MKV, with side-by-side / top-bottom stereo metadata, so a film
// needs no separate encoding pass. What carries the stereo flag, checked
// with ffprobe on ffmpeg 5.1 (docs/sequencer.md):
//   MKV, either codec: the track's StereoMode (ffmpeg's stream metadata
//       stereo_mode=left_right / top_bottom); ffprobe: side data "Stereo 3D".
//   MP4: the 'st3d' box (Google's spatial media, what YouTube reads), written by
//       remuxing a stereo MKV with -strict unofficial when the film is closed.
//   H.264, either container: also the frame-packing SEI (x264 frame-packing=3
//       side by side, 4 top-bottom), which 3D TVs and players read.
//   libx265 in Debian 12 has no frame-packing SEI option.
// The film appears under its name only when complete (written beside it
// under a temporary name, then renamed); a video export is not resumable.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

#include "core/image.h"
#include "sequencer/frame_range.h"
#include "sequencer/stereo_layout.h"

namespace hs::sequencer {

enum class VideoCodec : uint8_t { H264, H265 };
enum class VideoContainer : uint8_t { Mp4, Mkv };

// .mp4 / .mov -> Mp4, .mkv -> Mkv; nullopt for anything else (an image sequence).
std::optional<VideoContainer> videoContainerFromPath(const std::string& path);

struct VideoSettings {
  VideoCodec codec = VideoCodec::H264;
  int crf = 18;                    // quality: lower is better (x264/x265 CRF)
  std::string preset = "medium";   // x264/x265 speed preset
  int width = 3840;                // frame size (the layout's, not one eye's)
  int height = 1080;
  FrameRate rate{60, 1};
  StereoLayout layout = StereoLayout::SideBySide;  // decides the stereo metadata
  std::string ffmpeg = "ffmpeg";   // program (PATH lookup)
  int threads = 0;                 // encoder threads, 0 = ffmpeg's choice
};

// Whether `program` runs (`ffmpeg -version`).
bool ffmpegAvailable(const std::string& program = "ffmpeg");

// The ffmpeg command line that encodes raw RGBA from stdin into `output`.
std::vector<std::string> ffmpegEncodeArguments(const std::string& output, const VideoSettings& s);

class VideoWriter {
 public:
  // Starts ffmpeg. nullptr with `error` if it cannot start or the folder is missing.
  static std::unique_ptr<VideoWriter> open(const std::string& path, const VideoSettings& settings, std::string& error);
  ~VideoWriter();  // an unclosed writer stops ffmpeg and removes its temporary file
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // One frame, in order, of the settings' size (8-bit or float; float is
  // encoded to sRGB). False with `error` (ffmpeg's last words) if ffmpeg died.
  bool writeFrame(const Image& frame, std::string& error);
  // Finishes the film: waits for ffmpeg, adds the MP4 stereo box, renames into place.
  bool close(std::string& error);

  const std::string& path() const { return path_; }
  int64_t framesWritten() const { return frames_; }

 private:
  VideoWriter() = default;
  std::string lastLog() const;
  bool finishProcess(std::string& error);
  void abort();

  std::string path_, tempPath_, logPath_;
  VideoSettings settings_;
  pid_t pid_ = -1;
  int pipe_ = -1;
  int64_t frames_ = 0;
  bool closed_ = false;
  std::vector<uint8_t> scratch_;
};

}  // namespace hs::sequencer
