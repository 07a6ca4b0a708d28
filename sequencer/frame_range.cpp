#include "sequencer/frame_range.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace hs::sequencer {

double frameTime(int64_t frame, FrameRate rate) {
  // Exact while frame * den < 2^53 (any film: 2^53 / 1001 frames is 285 years at 1000 fps).
  return double(frame * rate.den) / double(rate.num);
}

int64_t frameAtTime(double t, FrameRate rate) {
  return int64_t(std::floor(t * double(rate.num) / double(rate.den) + 0.5));
}

std::optional<FrameRate> parseFrameRate(std::string_view text, std::string& error) {
  auto fail = [&]() -> std::optional<FrameRate> {
    error = "frame rate '" + std::string(text) + "': expected a rate like 60, 59.94 or 60000/1001";
    return std::nullopt;
  };
  if (const size_t slash = text.find('/'); slash != std::string_view::npos) {
    int64_t num = 0, den = 0;
    const auto a = text.substr(0, slash), b = text.substr(slash + 1);
    if (std::from_chars(a.data(), a.data() + a.size(), num).ec != std::errc() ||
        std::from_chars(b.data(), b.data() + b.size(), den).ec != std::errc() || num <= 0 || den <= 0)
      return fail();
    return FrameRate{num, den};
  }
  double fps = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), fps);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !(fps > 0.0) || fps > 10000.0) return fail();
  // The NTSC rates by their usual decimal names.
  for (int64_t base : {24, 30, 48, 60, 120})
    if (std::abs(fps - double(base) * 1000.0 / 1001.0) < 0.006) return FrameRate{base * 1000, 1001};
  if (std::abs(fps - std::round(fps)) < 1e-9) return FrameRate{int64_t(std::llround(fps)), 1};
  return FrameRate{int64_t(std::llround(fps * 1000.0)), 1000};
}

FrameList FrameList::range(int64_t first, int64_t last) {
  FrameList l;
  if (last < first) return l;
  l.spans_.push_back({first, last, 1});
  l.count_ = last - first + 1;
  return l;
}

FrameList FrameList::fromFrames(std::vector<int64_t> frames) {
  FrameList l;
  l.normalize(std::move(frames));
  return l;
}

void FrameList::normalize(std::vector<int64_t> frames) {
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  spans_.clear();
  count_ = int64_t(frames.size());
  // Runs with a constant step; a step-1 run is what export ranges are.
  size_t i = 0;
  while (i < frames.size()) {
    size_t j = i + 1;
    if (j < frames.size()) {
      const int64_t step = frames[j] - frames[i];
      while (j + 1 < frames.size() && frames[j + 1] - frames[j] == step) ++j;
      if (j - i >= 2 || step == 1) {
        spans_.push_back({frames[i], frames[j], step});
        i = j + 1;
        continue;
      }
    }
    spans_.push_back({frames[i], frames[i], 1});
    ++i;
  }
}

std::optional<FrameList> FrameList::parse(std::string_view text, std::string& error) {
  const std::string quoted = "frame range '" + std::string(text) + "'";
  std::vector<FrameSpan> items;
  size_t pos = 0;
  auto skipSpaces = [&] {
    while (pos < text.size() && (text[pos] == ' ' || text[pos] == '\t')) ++pos;
  };
  auto number = [&](int64_t& out) -> bool {
    skipSpaces();
    const auto r = std::from_chars(text.data() + pos, text.data() + text.size(), out);
    if (r.ec != std::errc()) return false;
    pos = size_t(r.ptr - text.data());
    skipSpaces();
    return true;
  };
  auto at = [&](size_t p) { return " at character " + std::to_string(p + 1); };
  skipSpaces();
  if (pos == text.size()) {
    error = quoted + ": empty; expected frames like 0-35999 or 10,20-30";
    return std::nullopt;
  }
  int64_t total = 0;
  while (true) {
    skipSpaces();
    if (pos == text.size() || text[pos] == ',') {
      error = quoted + ": empty item" + at(pos);
      return std::nullopt;
    }
    FrameSpan span;
    const size_t start = pos;
    if (!number(span.first)) {
      error = quoted + ": expected a frame number" + at(pos);
      return std::nullopt;
    }
    span.last = span.first;
    if (pos < text.size() && text[pos] == '-') {
      ++pos;
      if (!number(span.last)) {
        error = quoted + ": expected the last frame after '-'" + at(pos);
        return std::nullopt;
      }
      if (span.last < span.first) {
        error = quoted + ": range " + std::to_string(span.first) + "-" + std::to_string(span.last) +
                " runs backwards" + at(start);
        return std::nullopt;
      }
      if (pos < text.size() && (text[pos] == 'x' || text[pos] == ':')) {
        ++pos;
        if (!number(span.step) || span.step <= 0) {
          error = quoted + ": expected a positive step after 'x'" + at(pos);
          return std::nullopt;
        }
      }
    }
    total += (span.last - span.first) / span.step + 1;
    if (total > 100'000'000) {
      error = quoted + ": more than 100 million frames";
      return std::nullopt;
    }
    items.push_back(span);
    if (pos == text.size()) break;
    if (text[pos] != ',') {
      error = quoted + ": unexpected '" + std::string(1, text[pos]) + "'" + at(pos);
      return std::nullopt;
    }
    ++pos;
  }
  // Fast path: one plain span (the usual "0-35999").
  FrameList l;
  if (items.size() == 1 && items[0].step == 1) {
    l.spans_ = items;
    l.count_ = items[0].last - items[0].first + 1;
    return l;
  }
  std::vector<int64_t> frames;
  frames.reserve(size_t(total));
  for (const FrameSpan& s : items)
    for (int64_t f = s.first; f <= s.last; f += s.step) frames.push_back(f);
  l.normalize(std::move(frames));
  return l;
}

int64_t FrameList::first() const { return spans_.empty() ? 0 : spans_.front().first; }
int64_t FrameList::last() const { return spans_.empty() ? 0 : spans_.back().last; }

bool FrameList::contains(int64_t frame) const {
  for (const FrameSpan& s : spans_)
    if (frame >= s.first && frame <= s.last && (frame - s.first) % s.step == 0) return true;
  return false;
}

std::vector<int64_t> FrameList::frames() const {
  std::vector<int64_t> out;
  out.reserve(size_t(count_));
  for (const FrameSpan& s : spans_)
    for (int64_t f = s.first; f <= s.last; f += s.step) out.push_back(f);
  return out;
}

std::string FrameList::toString() const {
  std::string out;
  for (const FrameSpan& s : spans_) {
    if (!out.empty()) out += ',';
    out += std::to_string(s.first);
    if (s.last != s.first) {
      out += '-' + std::to_string(s.last);
      if (s.step != 1) out += 'x' + std::to_string(s.step);
    }
  }
  return out;
}

std::vector<FrameList> FrameList::chunks(int64_t chunkSize) const {
  std::vector<FrameList> out;
  if (chunkSize <= 0 || empty()) return out;
  FrameList current;
  for (const FrameSpan& s : spans_) {
    int64_t f = s.first;
    while (f <= s.last) {
      const int64_t room = chunkSize - current.count_;
      const int64_t available = (s.last - f) / s.step + 1;
      const int64_t take = std::min(room, available);
      const int64_t last = f + (take - 1) * s.step;
      current.spans_.push_back({f, last, take == 1 ? 1 : s.step});
      current.count_ += take;
      f = last + s.step;
      if (current.count_ == chunkSize) {
        out.push_back(std::move(current));
        current = FrameList();
      }
    }
  }
  if (!current.empty()) out.push_back(std::move(current));
  return out;
}

}  // namespace hs::sequencer
