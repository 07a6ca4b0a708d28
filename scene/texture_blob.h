#pragma once
// A standalone texture (scene/material.h) as a .hscene blob
// ("texture/<id>"): a small header, then the source file's bytes when it
// had any (PNG, JPEG: compact), else the decoded RGBA8. Decoding checks
// every size against the bytes present.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mesh/mesh_data.h"

namespace hs::scene {

std::vector<uint8_t> encodeTexture(const mesh::Texture& texture);
// `what` names the texture in messages.
std::optional<mesh::Texture> decodeTexture(const uint8_t* data, size_t size, const std::string& what,
                                           std::string& error);
// XXH3 of the decoded image (size and RGBA8): what the description stores.
uint64_t textureContentHash(const mesh::Texture& texture);

}  // namespace hs::scene
