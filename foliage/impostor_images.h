#pragma once
// The far level of a plant as the renderer baked it (render/impostor_cache.h
// bakes, render/impostor_atlas.h lays out the frames): two RGBA8 atlases of
// frames x frames pictures of framePixels^2 each, their level 0 only (the
// mip levels are rebuilt on upload). A mesh asset keeps one in the .hscene
// (blob "mesh/<id>/impostor", scene/scene_state.h) so that a scene opens
// without baking and every render node draws the same picture, whatever its
// GPU. sourceKey says what it was baked from (scene/impostor_key.h): when the
// mesh or its materials change, the stored images are stale and the renderer
// bakes its own until they are baked again.
//
// Blob (little endian):
//   "HSIM" | u16 version=1 | u16 frames | u16 framePixels | u16 0
//   | f32 sphere[4] | u64 sourceKey | u32 raw bytes | u32 payload bytes
//   | u64 XXH3 of the raw images (albedo then normalDepth) | payload
// payload: the raw images as a zlib stream after a filter: each channel as
// a plane, each byte minus its left neighbour's (atlases are mostly empty
// or smooth, which deflate then packs about tenfold). A decoder checks
// every field, the sizes and the hash, and says what is wrong and where.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace hs::foliage {

// The layout the renderer bakes (render/impostor_atlas.h explains it):
// frames per side of the grid (144 frames) and pixels per side of a frame
// (a 768 x 768 atlas). Images of another layout are stale.
inline constexpr int kImpostorFrames = 12;
inline constexpr int kImpostorFramePixels = 64;

struct ImpostorImages {
  int frames = 0;       // per side of the frame grid
  int framePixels = 0;  // per side of a frame
  glm::vec4 sphere{0.0f};  // level 0's bounds baked: centre (mesh space), radius
  uint64_t sourceKey = 0;  // what it was baked from (scene::impostorSourceKey)
  // side() x side() RGBA8 each, rows bottom up (GL's order): sRGB base
  // colour x coverage and coverage; (normal x 0.5 + 0.5, depth) x coverage.
  std::vector<uint8_t> albedo, normalDepth;

  int side() const { return frames * framePixels; }
  size_t imageBytes() const { return size_t(side()) * size_t(side()) * 4; }
  // XXH3 of both images: what the scene's description stores.
  uint64_t contentHash() const;
};

// The blob of `images` (see above); `level` is libdeflate's (1 .. 12).
std::vector<uint8_t> encodeImpostor(const ImpostorImages& images, int level = 6);
// `what` names the blob in messages ("scene.hscene: mesh asset 3 ('Pine'), impostor").
std::optional<ImpostorImages> decodeImpostor(std::span<const uint8_t> blob, const std::string& what,
                                             std::string& error);

}  // namespace hs::foliage
