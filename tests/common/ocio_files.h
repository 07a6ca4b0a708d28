#pragma once
// OpenColorIO configs written by tests (scene/ocio_config.h reads them):
// a small studio config with a film view whose curve is a 1D LUT under its
// search path, a raw view, two displays; and an ACES-style one whose
// reference is ACES2065-1 (an 'aces_interchange' role) with no transform to
// its output, so the renderer's conversion into it shows unchanged.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "lut_files.h"

namespace hs::test {

// The film curve the config's LUT holds: scene light in [0, 16] to display
// code values, a Reinhard-like shoulder reaching 1 at 16, then a 1/2.2 power.
inline double filmCurve(double x) {
  x = std::clamp(x, 0.0, 16.0);
  return std::pow(x / (1.0 + x) * (17.0 / 16.0), 1.0 / 2.2);
}

// An .spi1d table of filmCurve over [0, 16].
inline std::string filmSpi1d(int length = 4096) {
  std::string s = "Version 1\nFrom 0.0 16.0\nLength " + std::to_string(length) + "\nComponents 1\n{\n";
  char line[48];
  for (int i = 0; i < length; ++i) {
    std::snprintf(line, sizeof line, "  %.7f\n", filmCurve(16.0 * i / (length - 1)));
    s += line;
  }
  return s + "}\n";
}

// The studio config's text; `lut` is the film view's file (under the
// search path `searchPath`), `extra` more lines at the end.
inline std::string studioConfigText(const std::string& searchPath = "luts", const std::string& lut = "film.spi1d",
                                    const std::string& sceneLinearRole = "scene_linear") {
  return "ocio_profile_version: 2\n"
         "\n"
         "search_path: " + searchPath + "\n"
         "strictparsing: true\n"
         "\n"
         "roles:\n"
         "  default: raw\n"
         "  " + sceneLinearRole + ": linear\n"
         "\n"
         "file_rules:\n"
         "  - !<Rule> {name: Default, colorspace: default}\n"
         "\n"
         "displays:\n"
         "  Studio sRGB:\n"
         "    - !<View> {name: Film, colorspace: film}\n"
         "    - !<View> {name: Raw, colorspace: raw}\n"
         "  Projector:\n"
         "    - !<View> {name: Film, colorspace: film}\n"
         "\n"
         "active_displays: [Studio sRGB, Projector]\n"
         "active_views: [Film, Raw]\n"
         "\n"
         "colorspaces:\n"
         "  - !<ColorSpace>\n"
         "    name: linear\n"
         "    isdata: false\n"
         "\n"
         "  - !<ColorSpace>\n"
         "    name: raw\n"
         "    isdata: true\n"
         "\n"
         "  - !<ColorSpace>\n"
         "    name: film\n"
         "    isdata: false\n"
         "    from_reference: !<FileTransform> {src: " + lut + ", interpolation: linear}\n";
}

// Writes the studio config as `dir`/studio.ocio with its LUT in
// `dir`/luts/film.spi1d; the config's path.
inline std::string writeStudioConfig(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir / "luts");
  writeText((dir / "luts" / "film.spi1d").string(), filmSpi1d());
  const std::string path = (dir / "studio.ocio").string();
  writeText(path, studioConfigText());
  return path;
}

// A config whose reference is ACES2065-1 and whose one view shows it
// unchanged: what the renderer gives it is its conversion into ACES.
inline std::string acesConfigText() {
  return "ocio_profile_version: 2\n"
         "roles:\n"
         "  default: ACES2065-1\n"
         "  aces_interchange: ACES2065-1\n"
         "  scene_linear: ACES2065-1\n"
         "file_rules:\n"
         "  - !<Rule> {name: Default, colorspace: default}\n"
         "displays:\n"
         "  Check:\n"
         "    - !<View> {name: AP0, colorspace: ACES2065-1}\n"
         "active_displays: [Check]\n"
         "active_views: [AP0]\n"
         "colorspaces:\n"
         "  - !<ColorSpace>\n"
         "    name: ACES2065-1\n"
         "    isdata: false\n";
}

}  // namespace hs::test
