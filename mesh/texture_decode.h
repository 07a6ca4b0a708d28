#pragma once
// Image decoding for mesh textures through OpenImageIO: files on disk and
// images embedded in FBX/glTF. Output is always RGBA8, sRGB-encoded.
#include <cstdint>
#include <span>
#include <string>

#include "mesh/mesh_data.h"

namespace hs::mesh {

// Both return false and fill `error` (naming `what`) on failure.
bool decodeTextureFile(const std::string& path, Texture& out, std::string& error);
// `formatHint` is a file extension without the dot ("png", "jpg") when known.
bool decodeTextureMemory(std::span<const uint8_t> bytes, const std::string& formatHint,
                         const std::string& what, Texture& out, std::string& error);
// Decodes `texture.encoded` into `texture.rgba` (used when loading a scene file).
bool decodeTextureInPlace(Texture& texture, std::string& error);

}  // namespace hs::mesh
