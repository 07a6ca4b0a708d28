#pragma once
// Frame numbers, frame rates and frame lists ("0-35999", "10,20-30",
// "0-100x10"): what an export or a farm chunk renders.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/params.h"

namespace hs::sequencer {

// A rational rate so 59.94 (60000/1001) is exact and frame times are
// computed as frame * den / num in one correctly rounded division: frame
// 60,000,000 at 60 fps is t = 1e6 s exactly, not 1e6 +- accumulated error.
struct FrameRate {
  int64_t num = 60;
  int64_t den = 1;
  double fps() const { return double(num) / double(den); }
  bool operator==(const FrameRate&) const = default;
};

double frameTime(int64_t frame, FrameRate rate);
// The frame whose time is nearest `t` (ties to the later frame).
int64_t frameAtTime(double t, FrameRate rate);
// "60", "59.94", "60000/1001", "29.97", "23.976"; nullopt if not a rate.
std::optional<FrameRate> parseFrameRate(std::string_view text, std::string& error);

// An inclusive run of frames, first <= last, every `step` frames.
struct FrameSpan {
  int64_t first = 0;
  int64_t last = 0;
  int64_t step = 1;
  bool operator==(const FrameSpan&) const = default;
};

// A sorted list of distinct frames, kept as spans (36,000 frames is one span).
class FrameList {
 public:
  FrameList() = default;
  static FrameList range(int64_t first, int64_t last);  // inclusive
  static FrameList fromFrames(std::vector<int64_t> frames);

  // "0-35999", "10,20-30", "7", "0-100x10" (every 10th), spaces allowed.
  // Frames may be negative ("-5--1"). Overlaps are merged. On failure,
  // nullopt and `error` says where: "frame range '10,,20': empty item at
  // character 4".
  static std::optional<FrameList> parse(std::string_view text, std::string& error);

  bool empty() const { return count_ == 0; }
  int64_t count() const { return count_; }
  int64_t first() const;
  int64_t last() const;
  bool contains(int64_t frame) const;
  const std::vector<FrameSpan>& spans() const { return spans_; }
  std::vector<int64_t> frames() const;  // expanded, ascending
  // The canonical text ("0-599,1200-1799"), which parse() reads back.
  std::string toString() const;
  // Consecutive pieces of at most `chunkSize` frames each, in order: the
  // farm's job-array tasks.
  std::vector<FrameList> chunks(int64_t chunkSize) const;

  bool operator==(const FrameList& o) const { return spans_ == o.spans_; }

 private:
  void normalize(std::vector<int64_t> frames);
  std::vector<FrameSpan> spans_;
  int64_t count_ = 0;
};

// A frame number a user gives an operation (render and farm --frames,
// sequence --range, the timeline's range, the Export dialog): 0 ..
// 2^31-1. Frames before 0 would be times before the timeline starts, and
// 2^31 frames are more than a year of film at 60 fps.
const ParamDecl& frameNumberDecl();
// False with `error` ("--frames: frame -5 is out of range (0 to 2147483647)")
// when the list reaches outside frameNumberDecl(); `name` names the option.
bool checkFrameBounds(const FrameList& frames, const std::string& name, std::string& error);

}  // namespace hs::sequencer
