#include "sequencer/frame_verify.h"

#include <algorithm>
#include <filesystem>

#include "core/image_io.h"
#include "core/parallel.h"
#include "sequencer/frame_structure.h"
#include "sequencer/output_pattern.h"

namespace hs::sequencer {

std::string frameDescription(const std::string& jobTag) { return "Hybridscape frame; job " + jobTag; }

FrameCheck checkFrameFile(const std::string& path, int width, int height, const std::string& jobTag, bool deep) {
  FrameCheck c;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    c.missing = true;
    c.problem = path + ": missing";
    return c;
  }
  std::string why;
  auto in = image_io::open(path, why);
  if (!in) {
    c.problem = path + ": not a readable image (" + why + ")";
    return c;
  }
  const image_io::Spec& spec = in->spec();
  if (spec.width != width || spec.height != height) {
    c.problem = path + ": " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + ", expected " +
                std::to_string(width) + "x" + std::to_string(height);
    return c;
  }
  if (!jobTag.empty()) {
    const std::string desc = spec.attribute("ImageDescription");
    if (desc != frameDescription(jobTag)) {
      c.problem = path + ": written by another export (its description is '" + desc + "')";
      return c;
    }
  }
  // The file's end by its structure (a read, no decode); what the walk does
  // not know is decoded.
  bool unknown = false;
  if (const std::string problem = frameStructureProblem(path, unknown); !problem.empty()) {
    c.problem = path + ": damaged (" + problem + ")";
    return c;
  }
  if (deep || unknown) {
    std::vector<uint8_t> pixels(size_t(spec.width) * size_t(spec.height) * size_t(spec.channels) * 4);
    // A decoder may complain and still return true: libjpeg fills a JPEG
    // cut short with grey and only warns ("Premature end of JPEG file").
    if (std::string complaint; !in->read(spec.channels, image_io::PixelType::Float, pixels.data(), complaint)) {
      c.problem = path + ": damaged (" + complaint + ")";
      return c;
    }
  }
  c.ok = true;
  return c;
}

VerifyReport verifyFrames(const VerifySettings& s) {
  VerifyReport r;
  std::string error;
  const auto pattern = OutputPattern::parse(s.outputPattern, error);
  if (!pattern) {
    r.error = error;
    return r;
  }
  const std::vector<int64_t> frames = s.frames.frames();
  r.expectedFrames = int64_t(frames.size());
  const glm::ivec2 size = layoutFrameSize(s.layout, s.eyeWidth, s.eyeHeight);
  std::vector<FrameCheck> results(frames.size());
  parallelTasks(frames.size(), unsigned(std::max(1, s.threads)), [&](size_t i, unsigned) {
    FrameCheck worst;
    worst.ok = true;
    const int files = layoutFilesPerFrame(s.layout);
    for (int e = 0; e < files && worst.ok; ++e) {
      const Eye eye = files == 1 ? Eye::Both : (e == 0 ? Eye::Left : Eye::Right);
      worst = checkFrameFile(pattern->path(frames[i], eye), size.x, size.y, s.jobTag, s.deep);
    }
    results[i] = worst;
  });

  std::vector<bool> badChunk;
  for (size_t i = 0; i < frames.size(); ++i) {
    const FrameCheck& c = results[i];
    if (c.ok) {
      ++r.validFrames;
      continue;
    }
    if (c.missing) r.missing.push_back(frames[i]);
    else r.invalid.emplace_back(frames[i], c.problem);
    if (s.chunkSize > 0) {
      const size_t chunk = i / size_t(s.chunkSize);  // chunks() cuts the list every chunkSize frames
      if (badChunk.size() <= chunk) badChunk.resize(chunk + 1, false);
      badChunk[chunk] = true;
    }
  }
  for (size_t c = 0; c < badChunk.size(); ++c)
    if (badChunk[c]) r.chunksToRerun.push_back(int64_t(c));
  return r;
}

std::string VerifyReport::summary() const {
  if (!error.empty()) return error + "\n";
  std::string out = std::to_string(validFrames) + " of " + std::to_string(expectedFrames) + " frames valid";
  if (complete()) return out + "\n";
  out += "; " + std::to_string(missing.size()) + " missing, " + std::to_string(invalid.size()) + " invalid\n";
  if (!missing.empty()) out += "missing frames: " + FrameList::fromFrames(missing).toString() + "\n";
  const size_t shown = std::min<size_t>(invalid.size(), 20);
  for (size_t i = 0; i < shown; ++i) out += "invalid frame " + std::to_string(invalid[i].first) + ": " + invalid[i].second + "\n";
  if (invalid.size() > shown) out += "... and " + std::to_string(invalid.size() - shown) + " more invalid frames\n";
  if (!chunksToRerun.empty()) {
    std::vector<int64_t> c(chunksToRerun.begin(), chunksToRerun.end());
    out += "chunks (job-array tasks) to run again: " + FrameList::fromFrames(c).toString() + "\n";
  }
  return out;
}

}  // namespace hs::sequencer
