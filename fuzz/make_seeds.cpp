// Writes the seed corpora under fuzz/corpus/ from the test fixtures and
// from our own encoders, so the seeds are what the program really reads
// and writes. Not built by default; run when an encoder changes:
//   cmake --build build --target make_fuzz_seeds && build/fuzz/make_fuzz_seeds fuzz/corpus
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/json.h"
#include "mesh/byte_source.h"
#include "mesh/mesh_import.h"
#include "scene/demo_scene.h"
#include "scene/mesh_blob.h"
#include "scene/scene_json.h"
#include "sequencer/sequence_json.h"
#include "terrain/tile_blob.h"

namespace fs = std::filesystem;

namespace {

std::string readAll(const fs::path& p) {
  std::string bytes, error;
  if (!hs::mesh::readWholeFile(p.string(), bytes, error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    std::exit(1);
  }
  return bytes;
}

void put(const fs::path& dir, const std::string& name, const std::string& bytes) {
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << bytes;
}

template <class Bytes>
std::string str(const Bytes& b) {
  return std::string(reinterpret_cast<const char*>(b.data()), b.size());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_fuzz_seeds <fuzz/corpus>\n");
    return 2;
  }
  const fs::path out = argv[1];
  const fs::path data = HS_TEST_DATA_DIR "/mesh";

  put(out / "obj", "textured_quad.obj", readAll(data / "textured_quad.obj"));
  put(out / "obj", "polygons_and_refs.obj",
      "mtllib textured_quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\n"
      "usemtl quad\nf 1/1/1 2/2/1 3/3/1 4/1/1\nf -4 -3 -2\nl 1 2\np 3\nf 1 2 9\n");
  put(out / "mtl", "textured_quad.mtl", readAll(data / "textured_quad.mtl"));
  put(out / "mtl", "options.mtl", "newmtl a\nKd 0.1 0.2 0.3\nd 0.5\nmap_Kd -s 1 1 1 tex.png\nnewmtl b\nTr 0.25\n");
  put(out / "ply_check", "quad_and_triangle.ply", readAll(data / "quad_and_triangle.ply"));
  std::string binPly =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nelement tristrips 1\nproperty list int int vertex_indices\n"
      "end_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  binPly.append(reinterpret_cast<const char*>(v), sizeof v);
  const uint8_t three = 3;
  const int32_t face[3] = {0, 1, 2}, strip[5] = {4, 0, 1, 2, -1};
  binPly.append(reinterpret_cast<const char*>(&three), 1);
  binPly.append(reinterpret_cast<const char*>(face), sizeof face);
  binPly.append(reinterpret_cast<const char*>(strip), sizeof strip);
  put(out / "ply_check", "binary_faces_and_strips.ply", binPly);
  // stl_gltf_check: the first byte picks the check (odd: STL, 0: GLB, 2: glTF JSON).
  put(out / "stl_gltf_check", "textured_quad.glb", std::string(1, '\0') + readAll(data / "textured_quad.glb"));
  put(out / "stl_gltf_check", "ascii.stl",
      std::string(1, '\1') + "solid s\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n"
                             " endloop\nendfacet\nendsolid s\n");
  std::string stl(80, '\0');
  const uint32_t one = 1;
  stl.append(reinterpret_cast<const char*>(&one), 4);
  const float tri[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
  stl.append(reinterpret_cast<const char*>(tri), sizeof tri);
  stl.append(2, '\0');
  put(out / "stl_gltf_check", "binary.stl", std::string(1, '\1') + stl);

  std::string error;
  hs::mesh::ImportResult quad = hs::mesh::importMesh((data / "textured_quad.obj").string());
  if (!quad.ok()) {
    std::fprintf(stderr, "%s\n", quad.error.c_str());
    return 1;
  }
  put(out / "mesh_blob", "textured_quad.bin", str(hs::scene::encodeMesh(*quad.mesh)));

  hs::terrain::HeightfieldDesc desc;
  desc.samplesX = desc.samplesY = 257;
  desc.sizeMetres = {256.0, 256.0};
  hs::terrain::Terrain t = std::move(hs::terrain::Terrain::create(desc, {{}, {}}).value());
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) t.height.set(x, y, float((x * 7 + y * 3) % 97) * 0.25f);
  t.height.setHole(130, 5, true);
  put(out / "terrain_tile", "height.bin", str(hs::terrain::encodeHeightTile(t.height, 0)));
  put(out / "terrain_tile", "holes.bin", str(hs::terrain::encodeHolesTile(t.height, 1)));
  put(out / "terrain_tile", "paint.bin", str(hs::terrain::encodePaintTile(t.paint, 1, 2)));

  put(out / "scene_json", "starter.json", hs::writeJson(hs::scene::sceneToJson(hs::scene::buildStarterScene())));
  put(out / "sequence_json", "default.json", hs::sequencer::sequenceToJsonText(hs::sequencer::Sequence{}));
  return 0;
}
