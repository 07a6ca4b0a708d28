#pragma once
// A small log-log scatter/line plot rasterised by hand into an RGB image and
// written with OpenImageIO (there is no plotting package on the machines):
// axes with decade ticks, thick lines, markers, and a 5x7 bitmap font for
// labels (upper case, digits and a few signs).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace hs::bench {

struct Rgb {
  uint8_t r, g, b;
};

class Canvas {
 public:
  Canvas(int w, int h) : w_(w), h_(h), px_(size_t(w) * size_t(h) * 3, 255) {}
  int width() const { return w_; }
  int height() const { return h_; }

  void set(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= w_ || y >= h_) return;
    uint8_t* p = &px_[(size_t(y) * size_t(w_) + size_t(x)) * 3];
    p[0] = c.r, p[1] = c.g, p[2] = c.b;
  }
  void fillRect(int x0, int y0, int x1, int y1, Rgb c) {
    for (int y = std::min(y0, y1); y <= std::max(y0, y1); ++y)
      for (int x = std::min(x0, x1); x <= std::max(x0, x1); ++x) set(x, y, c);
  }
  // A line `thick` pixels wide (square brush stamped along a DDA walk).
  void line(double x0, double y0, double x1, double y1, Rgb c, int thick = 1) {
    const double len = std::max(std::abs(x1 - x0), std::abs(y1 - y0));
    const int steps = std::max(1, int(std::ceil(len)));
    const int r0 = -(thick - 1) / 2, r1 = thick / 2;
    for (int s = 0; s <= steps; ++s) {
      const double t = double(s) / steps;
      const int x = int(std::lround(x0 + (x1 - x0) * t)), y = int(std::lround(y0 + (y1 - y0) * t));
      for (int dy = r0; dy <= r1; ++dy)
        for (int dx = r0; dx <= r1; ++dx) set(x + dx, y + dy, c);
    }
  }
  // Filled marker: 0 circle, 1 square, 2 triangle, 3 diamond.
  void marker(double cx, double cy, int shape, Rgb c, int r = 5) {
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        bool in = false;
        switch (shape % 4) {
          case 0: in = dx * dx + dy * dy <= r * r; break;
          case 1: in = true; break;
          case 2: in = dy >= -r && std::abs(dx) * 2 <= (dy + r); break;
          case 3: in = std::abs(dx) + std::abs(dy) <= r; break;
        }
        if (in) set(int(std::lround(cx)) + dx, int(std::lround(cy)) + dy, c);
      }
  }
  // Text with its top-left at (x, y), `scale` pixels per font pixel.
  // Returns the width drawn.
  int text(int x, int y, const std::string& s, Rgb c, int scale = 2, bool vertical = false) {
    int pos = 0;
    for (char ch : s) {
      const auto& g = glyph(ch);
      for (int row = 0; row < 7; ++row)
        for (int col = 0; col < 5; ++col)
          if (g[size_t(row)][size_t(col)] == '#')
            for (int sy = 0; sy < scale; ++sy)
              for (int sx = 0; sx < scale; ++sx) {
                if (vertical)  // reading bottom to top
                  set(x + row * scale + sy, y - (pos + col * scale + sx), c);
                else
                  set(x + pos + col * scale + sx, y + row * scale + sy, c);
              }
      pos += 6 * scale;
    }
    return pos;
  }
  static int textWidth(const std::string& s, int scale = 2) { return int(s.size()) * 6 * scale; }

  bool savePng(const std::string& path, std::string& error) const {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
      error = path + ": cannot create a PNG writer";
      return false;
    }
    const OIIO::ImageSpec spec(w_, h_, 3, OIIO::TypeDesc::UINT8);
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, px_.data()) || !out->close()) {
      error = path + ": " + out->geterror();
      return false;
    }
    return true;
  }

 private:
  using Glyph = std::array<const char*, 7>;
  static const Glyph& glyph(char ch) {
    static const std::map<char, Glyph> font = {
        {' ', {".....", ".....", ".....", ".....", ".....", ".....", "....."}},
        {'0', {".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###."}},
        {'1', {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###."}},
        {'2', {".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####"}},
        {'3', {"#####", "...#.", "..#..", "...#.", "....#", "#...#", ".###."}},
        {'4', {"...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#."}},
        {'5', {"#####", "#....", "####.", "....#", "....#", "#...#", ".###."}},
        {'6', {"..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###."}},
        {'7', {"#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..."}},
        {'8', {".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###."}},
        {'9', {".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##.."}},
        {'A', {".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
        {'B', {"####.", "#...#", "#...#", "####.", "#...#", "#...#", "####."}},
        {'C', {".###.", "#...#", "#....", "#....", "#....", "#...#", ".###."}},
        {'D', {"###..", "#..#.", "#...#", "#...#", "#...#", "#..#.", "###.."}},
        {'E', {"#####", "#....", "#....", "####.", "#....", "#....", "#####"}},
        {'F', {"#####", "#....", "#....", "####.", "#....", "#....", "#...."}},
        {'G', {".###.", "#...#", "#....", "#.###", "#...#", "#...#", ".####"}},
        {'H', {"#...#", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
        {'I', {".###.", "..#..", "..#..", "..#..", "..#..", "..#..", ".###."}},
        {'J', {"..###", "...#.", "...#.", "...#.", "...#.", "#..#.", ".##.."}},
        {'K', {"#...#", "#..#.", "#.#..", "##...", "#.#..", "#..#.", "#...#"}},
        {'L', {"#....", "#....", "#....", "#....", "#....", "#....", "#####"}},
        {'M', {"#...#", "##.##", "#.#.#", "#.#.#", "#...#", "#...#", "#...#"}},
        {'N', {"#...#", "#...#", "##..#", "#.#.#", "#..##", "#...#", "#...#"}},
        {'O', {".###.", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
        {'P', {"####.", "#...#", "#...#", "####.", "#....", "#....", "#...."}},
        {'Q', {".###.", "#...#", "#...#", "#...#", "#.#.#", "#..#.", ".##.#"}},
        {'R', {"####.", "#...#", "#...#", "####.", "#.#..", "#..#.", "#...#"}},
        {'S', {".####", "#....", "#....", ".###.", "....#", "....#", "####."}},
        {'T', {"#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#.."}},
        {'U', {"#...#", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
        {'V', {"#...#", "#...#", "#...#", "#...#", "#...#", ".#.#.", "..#.."}},
        {'W', {"#...#", "#...#", "#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#."}},
        {'X', {"#...#", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", "#...#"}},
        {'Y', {"#...#", "#...#", ".#.#.", "..#..", "..#..", "..#..", "..#.."}},
        {'Z', {"#####", "....#", "...#.", "..#..", ".#...", "#....", "#####"}},
        {'.', {".....", ".....", ".....", ".....", ".....", ".##..", ".##.."}},
        {',', {".....", ".....", ".....", ".....", ".##..", "..#..", ".#..."}},
        {'-', {".....", ".....", ".....", "#####", ".....", ".....", "....."}},
        {'+', {".....", "..#..", "..#..", "#####", "..#..", "..#..", "....."}},
        {'=', {".....", ".....", "#####", ".....", "#####", ".....", "....."}},
        {'%', {"##...", "##..#", "...#.", "..#..", ".#...", "#..##", "...##"}},
        {'(', {"...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#."}},
        {')', {".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#..."}},
        {'/', {".....", "....#", "...#.", "..#..", ".#...", "#....", "....."}},
        {':', {".....", ".##..", ".##..", ".....", ".##..", ".##..", "....."}},
        {'^', {"..#..", ".#.#.", "#...#", ".....", ".....", ".....", "....."}},
        {'_', {".....", ".....", ".....", ".....", ".....", ".....", "#####"}},
        {'?', {".###.", "#...#", "....#", "...#.", "..#..", ".....", "..#.."}},
    };
    char u = ch >= 'a' && ch <= 'z' ? char(ch - 'a' + 'A') : ch;
    auto it = font.find(u);
    return it != font.end() ? it->second : font.at('?');
  }

  int w_, h_;
  std::vector<uint8_t> px_;
};

struct Series {
  std::string label;
  Rgb color;
  int markerShape = 0;
  bool dashed = false;
  std::vector<std::pair<double, double>> points;  // (x, y), both > 0, joined in this order
  std::vector<std::string> labels;                 // optional, one per point, drawn beside it
};

// One log-log panel into the rectangle (x0, y0)-(x1, y1) of the canvas.
inline void plotLogLog(Canvas& c, int x0, int y0, int x1, int y1, const std::string& title, const std::string& xLabel,
                       const std::string& yLabel, const std::vector<Series>& series) {
  double xmin = HUGE_VAL, xmax = -HUGE_VAL, ymin = HUGE_VAL, ymax = -HUGE_VAL;
  for (const auto& s : series)
    for (const auto& [x, y] : s.points)
      if (x > 0 && y > 0) xmin = std::min(xmin, x), xmax = std::max(xmax, x), ymin = std::min(ymin, y), ymax = std::max(ymax, y);
  if (!(xmin < HUGE_VAL)) return;
  const double lx0 = std::floor(std::log10(xmin)), lx1 = std::max(lx0 + 1, std::ceil(std::log10(xmax)));
  const double ly0 = std::floor(std::log10(ymin)), ly1 = std::max(ly0 + 1, std::ceil(std::log10(ymax)));
  const int left = x0 + 90, right = x1 - 20, top = y0 + 40, bottom = y1 - 60;
  auto px = [&](double x) { return left + (std::log10(x) - lx0) / (lx1 - lx0) * (right - left); };
  auto py = [&](double y) { return bottom - (std::log10(y) - ly0) / (ly1 - ly0) * (bottom - top); };
  const Rgb ink{30, 30, 30}, grid{225, 225, 225};
  // Decade grid and ticks.
  for (double e = lx0; e <= lx1; e += 1) {
    for (int k = 1; k < 10 && e + std::log10(k) <= lx1; ++k)
      c.line(px(k * std::pow(10, e)), top, px(k * std::pow(10, e)), bottom, grid);
    char buf[16];
    std::snprintf(buf, sizeof buf, "1E%d", int(e));
    c.text(int(px(std::pow(10, e))) - Canvas::textWidth(buf) / 2, bottom + 8, buf, ink);
  }
  for (double e = ly0; e <= ly1; e += 1) {
    for (int k = 1; k < 10 && e + std::log10(k) <= ly1; ++k)
      c.line(left, py(k * std::pow(10, e)), right, py(k * std::pow(10, e)), grid);
    char buf[16];
    std::snprintf(buf, sizeof buf, "1E%d", int(e));
    c.text(left - Canvas::textWidth(buf) - 8, int(py(std::pow(10, e))) - 7, buf, ink);
  }
  c.line(left, bottom, right, bottom, ink, 2);
  c.line(left, top, left, bottom, ink, 2);
  c.text((left + right - Canvas::textWidth(title)) / 2, y0 + 10, title, ink);
  c.text((left + right - Canvas::textWidth(xLabel)) / 2, bottom + 32, xLabel, ink);
  c.text(x0 + 10, (top + bottom + Canvas::textWidth(yLabel)) / 2, yLabel, ink, 2, true);
  // Series, then the legend in the upper right.
  int legendY = top + 10;
  for (const auto& s : series) {
    const auto& pts = s.points;
    for (size_t i = 1; i < pts.size(); ++i) {
      if (s.dashed && i % 2 == 0) continue;
      c.line(px(pts[i - 1].first), py(pts[i - 1].second), px(pts[i].first), py(pts[i].second), s.color, 2);
    }
    for (size_t i = 0; i < pts.size(); ++i) {
      c.marker(px(pts[i].first), py(pts[i].second), s.markerShape, s.color);
      if (i < s.labels.size()) c.text(int(px(pts[i].first)) + 8, int(py(pts[i].second)) - 12, s.labels[i], s.color, 1);
    }
    const int lx = right - Canvas::textWidth(s.label) - 40;
    c.line(lx, legendY + 7, lx + 24, legendY + 7, s.color, 2);
    c.marker(lx + 12, legendY + 7, s.markerShape, s.color);
    c.text(lx + 32, legendY, s.label, ink);
    legendY += 22;
  }
}

}  // namespace hs::bench
