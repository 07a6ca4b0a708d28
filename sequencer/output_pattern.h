#pragma once
// Output file names from a pattern: "frames/f_%05d.png" -> frames/f_00042.png.
// Accepted placeholders: one frame number, printf-style (%d, %05d) or as
// hashes (#####, Blender and Nuke's style: the count is the width); for
// separate eye sequences also %v (l / r) or %V (left / right), Nuke's names.
// "%%" is a literal percent sign.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace hs::sequencer {

enum class Eye : uint8_t { Left, Right, Both };

class OutputPattern {
 public:
  // nullopt with `error` naming the problem: no frame number, two frame
  // numbers, an unknown % sequence.
  static std::optional<OutputPattern> parse(std::string_view pattern, std::string& error);

  // The file of `frame`. For Eye::Left / Right without %v or %V in the
  // pattern, "_left" / "_right" goes before the extension
  // (f_00042_left.png), so separate sequences never overwrite each other.
  std::string path(int64_t frame, Eye eye = Eye::Both) const;

  bool hasEyePlaceholder() const { return eyeStyle_ != 0; }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
  std::string before_, between_, after_;  // around the frame number and the eye name
  int width_ = 0;
  bool eyeFirst_ = false;  // the eye placeholder comes before the frame number
  char eyeStyle_ = 0;      // 0, 'v' or 'V'
};

}  // namespace hs::sequencer
