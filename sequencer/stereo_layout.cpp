#include "sequencer/stereo_layout.h"

#include <algorithm>
#include <cstring>

#include "core/srgb.h"

namespace hs::sequencer {

const char* layoutName(StereoLayout l) {
  switch (l) {
    case StereoLayout::SideBySide: return "sbs";
    case StereoLayout::SideBySideSqueezed: return "sbs-half";
    case StereoLayout::TopBottom: return "tb";
    case StereoLayout::TopBottomSqueezed: return "tb-half";
    case StereoLayout::Separate: return "separate";
    case StereoLayout::Anaglyph: return "anaglyph";
    case StereoLayout::Mono: return "mono";
  }
  return "?";
}

std::optional<StereoLayout> layoutFromName(std::string_view s) {
  for (auto l : {StereoLayout::SideBySide, StereoLayout::SideBySideSqueezed, StereoLayout::TopBottom,
                 StereoLayout::TopBottomSqueezed, StereoLayout::Separate, StereoLayout::Anaglyph, StereoLayout::Mono})
    if (s == layoutName(l)) return l;
  if (s == "sbs-full" || s == "side-by-side") return StereoLayout::SideBySide;
  if (s == "sbs-squeezed" || s == "half-sbs") return StereoLayout::SideBySideSqueezed;
  if (s == "top-bottom" || s == "tab") return StereoLayout::TopBottom;
  if (s == "tb-squeezed" || s == "half-tab") return StereoLayout::TopBottomSqueezed;
  if (s == "left-right") return StereoLayout::Separate;
  return std::nullopt;
}

bool layoutRendersBothEyes(StereoLayout l) { return l != StereoLayout::Mono; }

glm::ivec2 layoutFrameSize(StereoLayout l, int w, int h) {
  switch (l) {
    case StereoLayout::SideBySide: return {2 * w, h};
    case StereoLayout::TopBottom: return {w, 2 * h};
    default: return {w, h};
  }
}

int layoutFilesPerFrame(StereoLayout l) { return l == StereoLayout::Separate ? 2 : 1; }

namespace {

// Copies `src` into `dst` at (x0, y0); same pixel kind.
void blit(Image& dst, const Image& src, int x0, int y0) {
  const bool f = src.isFloat();
  const size_t px = f ? 4 * sizeof(float) : 4;
  for (int y = 0; y < src.height; ++y) {
    const size_t srcOff = size_t(y) * size_t(src.width) * px;
    const size_t dstOff = (size_t(y + y0) * size_t(dst.width) + size_t(x0)) * px;
    if (f)
      std::memcpy(reinterpret_cast<uint8_t*>(dst.rgbaF.data()) + dstOff,
                  reinterpret_cast<const uint8_t*>(src.rgbaF.data()) + srcOff, size_t(src.width) * px);
    else
      std::memcpy(dst.rgba8.data() + dstOff, src.rgba8.data() + srcOff, size_t(src.width) * px);
  }
}

Image blank(const Image& like, int w, int h) { return like.isFloat() ? Image::makeF(w, h) : Image::make8(w, h); }

// One axis of area resampling: output sample i covers input [i*r, (i+1)*r).
// `count` samples of `stride` pixels apart, `lines` lines `lineStride` apart.
struct Axis {
  int inCount, outCount;
};

template <class Load, class Store>
void resampleAxis(const Axis& a, Load load, Store store) {
  const double ratio = double(a.inCount) / double(a.outCount);
  for (int o = 0; o < a.outCount; ++o) {
    const double lo = o * ratio, hi = (o + 1) * ratio;
    float acc[4] = {0, 0, 0, 0};
    double total = 0.0;
    for (int i = int(lo); i < a.inCount && double(i) < hi; ++i) {
      const double w = std::min(hi, double(i + 1)) - std::max(lo, double(i));
      if (w <= 0.0) continue;
      float px[4];
      load(i, px);
      for (int c = 0; c < 4; ++c) acc[c] += float(w) * px[c];
      total += w;
    }
    for (float& c : acc) c = float(double(c) / total);
    store(o, acc);
  }
}

Image resample(const Image& in, int outW, int outH) {
  Image out = blank(in, outW, outH);
  const bool horizontal = outW != in.width;
  const int lines = horizontal ? in.height : in.width;
  const Axis axis{horizontal ? in.width : in.height, horizontal ? outW : outH};
  for (int line = 0; line < lines; ++line) {
    auto inIndex = [&](int i) { return horizontal ? size_t(line) * size_t(in.width) + size_t(i)
                                                   : size_t(i) * size_t(in.width) + size_t(line); };
    auto outIndex = [&](int o) { return horizontal ? size_t(line) * size_t(outW) + size_t(o)
                                                    : size_t(o) * size_t(outW) + size_t(line); };
    if (in.isFloat()) {
      resampleAxis(axis, [&](int i, float* px) { std::memcpy(px, &in.rgbaF[inIndex(i) * 4], 4 * sizeof(float)); },
                   [&](int o, const float* px) { std::memcpy(&out.rgbaF[outIndex(o) * 4], px, 4 * sizeof(float)); });
    } else {
      resampleAxis(
          axis,
          [&](int i, float* px) {
            const uint8_t* p = &in.rgba8[inIndex(i) * 4];
            for (int c = 0; c < 3; ++c) px[c] = srgb8ToLinear(p[c]);
            px[3] = float(p[3]) / 255.0f;
          },
          [&](int o, const float* px) {
            uint8_t* p = &out.rgba8[outIndex(o) * 4];
            for (int c = 0; c < 3; ++c) p[c] = linearToSrgb8(px[c]);
            p[3] = uint8_t(std::lround(std::clamp(px[3], 0.0f, 1.0f) * 255.0f));
          });
    }
  }
  return out;
}

}  // namespace

Image resampleWidth(const Image& in, int width) {
  if (width == in.width || in.empty() || width <= 0) return in;
  return resample(in, width, in.height);
}

Image resampleHeight(const Image& in, int height) {
  if (height == in.height || in.empty() || height <= 0) return in;
  return resample(in, in.width, height);
}

std::vector<Image> composeLayout(StereoLayout layout, const Image& left, const Image& right, AnaglyphMethod method) {
  if (layout == StereoLayout::Mono) return {left};
  if (left.width != right.width || left.height != right.height || left.isFloat() != right.isFloat() || left.empty())
    return {};
  const int w = left.width, h = left.height;
  if ((layout == StereoLayout::SideBySideSqueezed && w < 2) || (layout == StereoLayout::TopBottomSqueezed && h < 2))
    return {};  // nothing to squeeze into halves
  switch (layout) {
    case StereoLayout::SideBySide: {
      Image out = blank(left, 2 * w, h);
      blit(out, left, 0, 0);
      blit(out, right, w, 0);
      return {std::move(out)};
    }
    case StereoLayout::TopBottom: {
      Image out = blank(left, w, 2 * h);
      blit(out, left, 0, 0);
      blit(out, right, 0, h);
      return {std::move(out)};
    }
    case StereoLayout::SideBySideSqueezed: {
      Image out = blank(left, w, h);
      blit(out, resampleWidth(left, w / 2), 0, 0);
      blit(out, resampleWidth(right, w - w / 2), w / 2, 0);
      return {std::move(out)};
    }
    case StereoLayout::TopBottomSqueezed: {
      Image out = blank(left, w, h);
      blit(out, resampleHeight(left, h / 2), 0, 0);
      blit(out, resampleHeight(right, h - h / 2), 0, h / 2);
      return {std::move(out)};
    }
    case StereoLayout::Separate: return {left, right};
    case StereoLayout::Anaglyph: return {makeAnaglyph(left, right, method)};
    case StereoLayout::Mono: break;
  }
  return {left};
}

}  // namespace hs::sequencer
