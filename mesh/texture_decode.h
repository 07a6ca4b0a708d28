#pragma once
// Image decoding for mesh textures through OpenImageIO: files on disk and
// images embedded in FBX/glTF. Output is always RGBA8, sRGB-encoded.
#include <cstdint>
#include <span>
#include <string>

#include "mesh/mesh_data.h"

namespace hs::mesh {

// Both return false and fill `error` (naming `what`) on failure. `note`,
// when given, is set when the image decodes but is drawn from less than it
// holds (channels beyond the fourth: "...: 5 channels (R, G, B, A, Z); drawn
// from the first 4, ..."), and left alone otherwise: the readers put it in
// the import report, so that less is never drawn without a word.
bool decodeTextureFile(const std::string& path, Texture& out, std::string& error, std::string* note = nullptr);
// `formatHint` is a file extension without the dot ("png", "jpg") when known.
bool decodeTextureMemory(std::span<const uint8_t> bytes, const std::string& formatHint,
                         const std::string& what, Texture& out, std::string& error, std::string* note = nullptr);
// Decodes `texture.encoded` into `texture.rgba` (used when loading a scene file).
bool decodeTextureInPlace(Texture& texture, std::string& error);

}  // namespace hs::mesh
