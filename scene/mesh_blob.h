#pragma once
// Binary encoding of a MeshData for the .hscene blob table: a small header,
// then the arrays as they are in memory (little-endian, which every target
// of this project is). Decoding checks every size against the bytes present,
// so a damaged blob is an error with a byte offset, never a crash.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mesh/mesh_data.h"

namespace hs::scene {

std::vector<uint8_t> encodeMesh(const mesh::MeshData& mesh);
// `what` names the blob in messages ("mesh asset 3"). A LOD level keeps
// its base's material list without copies of its textures
// (meshproc/lod_chain.h): `baseTextures`, the base's texture count, is
// how many textures its materials may name.
std::optional<mesh::MeshData> decodeMesh(const uint8_t* data, size_t size, const std::string& what,
                                         std::string& error, size_t baseTextures = 0);

}  // namespace hs::scene
