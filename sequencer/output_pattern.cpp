#include "sequencer/output_pattern.h"

#include <cstdio>
#include <filesystem>

namespace hs::sequencer {

std::optional<OutputPattern> OutputPattern::parse(std::string_view pattern, std::string& error) {
  OutputPattern p;
  p.text_ = std::string(pattern);
  const std::string quoted = "output pattern '" + std::string(pattern) + "'";
  std::string* part = &p.before_;
  bool haveFrame = false, haveEye = false;
  for (size_t i = 0; i < pattern.size(); ++i) {
    const char c = pattern[i];
    if (c == '#') {
      size_t j = i;
      while (j < pattern.size() && pattern[j] == '#') ++j;
      if (haveFrame) {
        error = quoted + ": more than one frame number";
        return std::nullopt;
      }
      haveFrame = true;
      p.width_ = int(j - i);
      part = haveEye ? &p.after_ : &p.between_;
      i = j - 1;
      continue;
    }
    if (c != '%') {
      *part += c;
      continue;
    }
    if (i + 1 >= pattern.size()) {
      error = quoted + ": '%' at the end; write %% for a percent sign";
      return std::nullopt;
    }
    if (pattern[i + 1] == '%') {
      *part += '%';
      ++i;
      continue;
    }
    if (pattern[i + 1] == 'v' || pattern[i + 1] == 'V') {
      if (haveEye) {
        error = quoted + ": more than one eye placeholder (%v or %V)";
        return std::nullopt;
      }
      haveEye = true;
      p.eyeStyle_ = pattern[i + 1];
      p.eyeFirst_ = !haveFrame;
      part = haveFrame ? &p.after_ : &p.between_;
      ++i;
      continue;
    }
    size_t j = i + 1;
    int width = 0;
    while (j < pattern.size() && pattern[j] >= '0' && pattern[j] <= '9') width = width * 10 + (pattern[j++] - '0');
    if (j >= pattern.size() || pattern[j] != 'd' || width > 18) {
      error = quoted + ": unknown placeholder at character " + std::to_string(i + 1) +
              "; use %05d or ##### for the frame number, %v or %V for the eye, %% for a percent sign";
      return std::nullopt;
    }
    if (haveFrame) {
      error = quoted + ": more than one frame number";
      return std::nullopt;
    }
    haveFrame = true;
    p.width_ = width;
    part = haveEye ? &p.after_ : &p.between_;
    i = j;
  }
  if (!haveFrame) {
    error = quoted + ": no frame number; add %05d (or #####), e.g. frames/f_%05d.png";
    return std::nullopt;
  }
  return p;
}

std::string OutputPattern::path(int64_t frame, Eye eye) const {
  char digits[32];
  std::snprintf(digits, sizeof digits, "%0*lld", width_, static_cast<long long>(frame));
  std::string eyeName;
  if (eye != Eye::Both && eyeStyle_)
    eyeName = eyeStyle_ == 'v' ? (eye == Eye::Left ? "l" : "r") : (eye == Eye::Left ? "left" : "right");
  std::string out = eyeFirst_ ? before_ + eyeName + between_ + digits + after_
                              : before_ + digits + between_ + eyeName + after_;
  if (eye != Eye::Both && !eyeStyle_) {
    std::filesystem::path fp(out);
    const std::string ext = fp.extension().string();
    out = out.substr(0, out.size() - ext.size()) + (eye == Eye::Left ? "_left" : "_right") + ext;
  }
  return out;
}

}  // namespace hs::sequencer
