#include "bench/terrain/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include <OpenImageIO/imageio.h>

namespace hs::bench {
namespace {

// 5x7 glyphs, one string of 7 rows x 5 columns ('#' = ink). Lower case is
// drawn as upper case.
const std::map<char, const char*>& font() {
  static const std::map<char, const char*> f = {
      {' ', "                                   "},
      {'0', " ### #   ##  ### # ###  ##   # ### "},
      {'1', "  #   ##    #    #    #    #   ### "},
      {'2', " ### #   #    #   #   #   #   #####"},
      {'3', "#####   #   #     #     ##   # ### "},
      {'4', "   #   ##  # # #  # #####   #    # "},
      {'5', "######    ####     #    ##   # ### "},
      {'6', "  ##  #   #    #### #   ##   # ### "},
      {'7', "#####    #   #   #   #    #    #   "},
      {'8', " ### #   ##   # ### #   ##   # ### "},
      {'9', " ### #   ##   # ####    #   #  ##  "},
      {'A', " ### #   ##   #######   ##   ##   #"},
      {'B', "#### #   ##   ##### #   ##   ##### "},
      {'C', " ### #   ##    #    #    #   # ### "},
      {'D', "#### #   ##   ##   ##   ##   ##### "},
      {'E', "######    #    #### #    #    #####"},
      {'F', "######    #    #### #    #    #    "},
      {'G', " ### #   ##    # ####   ##   # ####"},
      {'H', "#   ##   ##   #######   ##   ##   #"},
      {'I', " ###   #    #    #    #    #   ### "},
      {'J', "  ###   #    #    #    # #  #  ##  "},
      {'K', "#   ##  # # #  ##   # #  #  # #   #"},
      {'L', "#    #    #    #    #    #    #####"},
      {'M', "#   ### ### # ## # ##   ##   ##   #"},
      {'N', "#   ##   ###  ## # ##  ###   ##   #"},
      {'O', " ### #   ##   ##   ##   ##   # ### "},
      {'P', "#### #   ##   ##### #    #    #    "},
      {'Q', " ### #   ##   ##   ## # ##  #  ## #"},
      {'R', "#### #   ##   ##### # #  #  # #   #"},
      {'S', " #####    #     ###     #    ##### "},
      {'T', "#####  #    #    #    #    #    #  "},
      {'U', "#   ##   ##   ##   ##   ##   # ### "},
      {'V', "#   ##   ##   ##   ##   # # #   #  "},
      {'W', "#   ##   ##   ## # ## # ## # # # # "},
      {'X', "#   ##   # # #   #   # # #   ##   #"},
      {'Y', "#   ##   # # #   #    #    #    #  "},
      {'Z', "#####    #   #   #   #   #    #####"},
      {'.', "                          ##   ##  "},
      {',', "                     ##   ##  #    "},
      {'-', "               #####               "},
      {'+', "       #    #  #####  #    #       "},
      {'(', "   #   #   #    #    #     #     # "},
      {')', " #     #     #    #    #   #   #   "},
      {'/', "    #    #   #   #   #   #    #    "},
      {':', "      ##   ##        ##   ##       "},
      {'%', "##   ##  #   #   #   #   #  ##   ##"},
      {'=', "          #####     #####          "},
      {'^', "  #   # # #   #                    "},
      {'_', "                              #####"},
      {'[', " ###  #    #    #    #    #    ### "},
      {']', " ###    #    #    #    #    #  ### "},
      {'*', "     # # # ### ##### ### # # #     "},
      {'x', "          #   # # #   #   # # #   #"},

  };
  return f;
}

struct Canvas {
  int w, h;
  std::vector<float> rgb;
  void set(int x, int y, glm::vec3 c) {
    if (x < 0 || y < 0 || x >= w || y >= h) return;
    float* p = &rgb[(size_t(y) * size_t(w) + size_t(x)) * 3];
    p[0] = c.r; p[1] = c.g; p[2] = c.b;
  }
  void line(double x0, double y0, double x1, double y1, glm::vec3 c, int thick = 1) {
    const int steps = int(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) + 1;
    for (int i = 0; i <= steps; ++i) {
      const double t = double(i) / steps;
      const int x = int(std::lround(x0 + (x1 - x0) * t)), y = int(std::lround(y0 + (y1 - y0) * t));
      for (int dy = -(thick / 2); dy <= thick / 2; ++dy)
        for (int dx = -(thick / 2); dx <= thick / 2; ++dx) set(x + dx, y + dy, c);
    }
  }
  void square(int cx, int cy, int r, glm::vec3 c) {
    for (int y = -r; y <= r; ++y)
      for (int x = -r; x <= r; ++x) set(cx + x, cy + y, c);
  }
  // Text at (x, y) = top-left, scale s; vertical draws bottom-to-top.
  int text(int x, int y, const std::string& s, glm::vec3 c, int scale = 2, bool vertical = false) {
    int pen = 0;
    for (char ch : s) {
      char k = ch;
      if (k >= 'a' && k <= 'z' && k != 'x') k = char(k - 'a' + 'A');
      auto it = font().find(k);
      const char* g = it == font().end() ? font().at(' ') : it->second;
      for (int row = 0; row < 7; ++row)
        for (int col = 0; col < 5; ++col) {
          const size_t i = size_t(row * 5 + col);
          if (i >= std::char_traits<char>::length(g) || g[i] != '#') continue;
          for (int sy = 0; sy < scale; ++sy)
            for (int sx = 0; sx < scale; ++sx) {
              const int gx = pen + col * scale + sx, gy = row * scale + sy;
              if (vertical) set(x + gy, y - gx, c);
              else set(x + gx, y + gy, c);
            }
        }
      pen += 6 * scale;
    }
    return pen;
  }
};

std::string tickLabel(double v) {
  char b[32];
  const double e = std::log10(v);
  if (std::abs(e - std::round(e)) < 1e-9) {
    const int ie = int(std::round(e));
    if (ie >= -2 && ie <= 3) std::snprintf(b, sizeof b, "%g", v);
    else std::snprintf(b, sizeof b, "1e%d", ie);
  } else {
    std::snprintf(b, sizeof b, "%.3g", v);
  }
  return b;
}

}  // namespace

std::string drawPlot(const PlotSpec& spec, const std::vector<Series>& series, const std::string& path) {
  Canvas c{spec.width, spec.height, std::vector<float>(size_t(spec.width) * size_t(spec.height) * 3, 1.0f)};
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& s : series)
    for (const auto& p : s.points) {
      if (!(p.x > 0 && p.y > 0)) continue;
      x0 = std::min(x0, p.x); x1 = std::max(x1, p.x);
      y0 = std::min(y0, p.y); y1 = std::max(y1, p.y);
    }
  if (x0 > x1) return "nothing to plot";
  // Whole decades around the data.
  const double lx0 = std::floor(std::log10(x0)), lx1 = std::max(lx0 + 1, std::ceil(std::log10(x1)));
  const double ly0 = std::floor(std::log10(y0)), ly1 = std::max(ly0 + 1, std::ceil(std::log10(y1)));
  const int L = 110, R = spec.width - 30, T = 50, B = spec.height - 70;
  auto px = [&](double x) { return L + (std::log10(x) - lx0) / (lx1 - lx0) * (R - L); };
  auto py = [&](double y) { return B - (std::log10(y) - ly0) / (ly1 - ly0) * (B - T); };
  const glm::vec3 ink(0.1f), grid(0.85f);
  for (double e = lx0; e <= lx1 + 1e-9; ++e) {
    for (int m = 2; m <= 9 && e < lx1; ++m) c.line(px(m * std::pow(10.0, e)), T, px(m * std::pow(10.0, e)), B, glm::vec3(0.94f));
    const double x = px(std::pow(10.0, e));
    c.line(x, T, x, B, grid);
    const std::string s = tickLabel(std::pow(10.0, e));
    c.text(int(x) - int(s.size()) * 6, B + 10, s, ink);
  }
  for (double e = ly0; e <= ly1 + 1e-9; ++e) {
    for (int m = 2; m <= 9 && e < ly1; ++m) c.line(L, py(m * std::pow(10.0, e)), R, py(m * std::pow(10.0, e)), glm::vec3(0.94f));
    const double y = py(std::pow(10.0, e));
    c.line(L, y, R, y, grid);
    const std::string s = tickLabel(std::pow(10.0, e));
    c.text(L - 8 - int(s.size()) * 12, int(y) - 7, s, ink);
  }
  c.line(L, B, R, B, ink, 2);
  c.line(L, T, L, B, ink, 2);
  c.text(L, 12, spec.title, ink, 2);
  c.text((L + R) / 2 - int(spec.xLabel.size()) * 6, spec.height - 30, spec.xLabel, ink, 2);
  c.text(20, (T + B) / 2 + int(spec.yLabel.size()) * 6, spec.yLabel, ink, 2, true);
  int legendY = T + 10;
  for (const auto& s : series) {
    for (size_t i = 1; i < s.points.size(); ++i)
      c.line(px(s.points[i - 1].x), py(s.points[i - 1].y), px(s.points[i].x), py(s.points[i].y), s.colour, 3);
    for (const auto& p : s.points) c.square(int(px(p.x)), int(py(p.y)), 4, s.colour);
    c.line(R - 360, legendY + 6, R - 330, legendY + 6, s.colour, 3);
    c.text(R - 320, legendY, s.name, ink, 2);
    legendY += 24;
  }
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return "cannot write " + path;
  OIIO::ImageSpec is(spec.width, spec.height, 3, OIIO::TypeDesc::UINT8);
  if (!out->open(path, is) || !out->write_image(OIIO::TypeDesc::FLOAT, c.rgb.data()) || !out->close())
    return "cannot write " + path + ": " + out->geterror();
  return {};
}

}  // namespace hs::bench
