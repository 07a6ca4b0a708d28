#pragma once
// How far from the world origin a position typed by a user may be: ±1e7 m
// on each axis. That holds every UTM coordinate (eastings up to about
// 834 km, northings up to 10,000 km) and any scene a film is made of, and
// a double there still resolves about 2 nm. A position far beyond it
// (`import --at 1e300,0,0`) is a typing error: the renderer's
// camera-relative maths then loses the scene entirely and renders nothing.
namespace hs {

inline constexpr double kWorldExtentMetres = 1e7;

}  // namespace hs
