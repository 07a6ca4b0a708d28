#pragma once
// Is a written frame there and valid? Used by export resume (which frames
// to keep) and by the farm's final step (`hybridscape-cli farm verify`):
// the same rule decides in both places.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sequencer/frame_range.h"
#include "sequencer/stereo_layout.h"

namespace hs::sequencer {

struct FrameCheck {
  bool ok = false;
  bool missing = false;  // no file at all (as opposed to a bad one)
  std::string problem;   // "frames/f_00042.png: 1920x1080, expected 3840x1080"
};

// A frame file is valid when it exists, OpenImageIO opens it, its header
// says width x height and the file is whole: a PNG's chunks and CRCs up to
// IEND, a JPEG's end marker, an EXR's chunks, a TIFF's strips all within the
// file (frame_structure.h); what that walk does not know is decoded.
// A frame cut short (a copy that stopped, a full disk) is caught by this
// default check, and resume renders it again. With a non-empty `jobTag`, its
// description must also carry that tag (so a resumed export never keeps
// frames of other settings). `deep` also decodes every pixel (catches
// damage inside the data that keeps the structure whole: a flipped bit in an
// EXR or JPEG, which has no checksum).
FrameCheck checkFrameFile(const std::string& path, int width, int height, const std::string& jobTag = {},
                          bool deep = false);

// What the image description says for a tag (written by the export loop).
std::string frameDescription(const std::string& jobTag);

struct VerifySettings {
  FrameList frames;
  std::string outputPattern;
  StereoLayout layout = StereoLayout::SideBySide;
  int eyeWidth = 1920;
  int eyeHeight = 1080;
  std::string jobTag;
  bool deep = false;
  int64_t chunkSize = 0;  // when > 0, the report names the chunks (job-array tasks) to run again
  int threads = 2;        // files are checked in parallel (network file systems are slow per file)
};

struct VerifyReport {
  int64_t expectedFrames = 0;
  int64_t validFrames = 0;
  std::vector<int64_t> missing;                         // frames with a missing file
  std::vector<std::pair<int64_t, std::string>> invalid;  // frames with a bad file, and why
  std::vector<int64_t> chunksToRerun;                   // array task indices, when chunkSize > 0
  std::string error;                                    // a bad pattern

  bool complete() const { return error.empty() && missing.empty() && invalid.empty(); }
  // Lines for a person: counts, the missing frames as ranges, the first bad
  // files with their problem, the chunks to run again.
  std::string summary() const;
};

VerifyReport verifyFrames(const VerifySettings& settings);

}  // namespace hs::sequencer
