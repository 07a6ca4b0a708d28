#pragma once
// 3D Tiles content written by the tests themselves, byte by byte from the
// specifications (glTF 2.0 GLB, b3dm 1.0, KHR_draco_mesh_compression
// through libdraco's encoder), and the WGS 84 geodesy to place and check
// it (east-north-up frames on the ellipsoid, ECEF to latitude and
// longitude by Bowring's iteration): independent of mesh/tileset_reader.h
// and of PROJ, which the import goes through. Header-only.
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/json.h"

namespace hs::test {

// WGS 84.
constexpr double kWgsA = 6378137.0, kWgsF = 1.0 / 298.257223563, kWgsE2 = kWgsF * (2.0 - kWgsF);

inline glm::dvec3 geodeticToEcef(double lonDeg, double latDeg, double h) {
  const double lon = glm::radians(lonDeg), lat = glm::radians(latDeg);
  const double n = kWgsA / std::sqrt(1.0 - kWgsE2 * std::sin(lat) * std::sin(lat));
  return {(n + h) * std::cos(lat) * std::cos(lon), (n + h) * std::cos(lat) * std::sin(lon),
          (n * (1.0 - kWgsE2) + h) * std::sin(lat)};
}

// (lon degrees, lat degrees, ellipsoidal height).
inline glm::dvec3 ecefToGeodetic(const glm::dvec3& x) {
  const double p = std::hypot(x.x, x.y), lon = std::atan2(x.y, x.x);
  double lat = std::atan2(x.z, p * (1.0 - kWgsE2)), h = 0.0;
  for (int i = 0; i < 20; ++i) {
    const double n = kWgsA / std::sqrt(1.0 - kWgsE2 * std::sin(lat) * std::sin(lat));
    h = p / std::cos(lat) - n;
    lat = std::atan2(x.z, p * (1.0 - kWgsE2 * n / (n + h)));
  }
  return {glm::degrees(lon), glm::degrees(lat), h};
}

// The east-north-up frame at a point as a column-major 4x4 (3D Tiles'
// tile.transform): local metres to ECEF.
inline glm::dmat4 enuToEcef(double lonDeg, double latDeg, double h) {
  const double lon = glm::radians(lonDeg), lat = glm::radians(latDeg);
  glm::dmat4 m(1.0);
  m[0] = {-std::sin(lon), std::cos(lon), 0.0, 0.0};
  m[1] = {-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon), std::cos(lat), 0.0};
  m[2] = {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat), 0.0};
  m[3] = glm::dvec4(geodeticToEcef(lonDeg, latDeg, h), 1.0);
  return m;
}

inline Json matrixJson(const glm::dmat4& m) {
  Json a = Json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) a.push_back(m[c][r]);
  return a;
}

// A grid of `cells` x `cells` quads over [e0, e1] x [n0, n1] (z up), two
// triangles each, heights from `height`.
struct TestGrid {
  std::vector<glm::dvec3> points;  // z up
  std::vector<uint32_t> triangles;
};
template <class Height>
TestGrid testGrid(double e0, double e1, double n0, double n1, int cells, Height height) {
  TestGrid g;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      const double e = e0 + (e1 - e0) * i / cells, n = n0 + (n1 - n0) * j / cells;
      g.points.push_back({e, n, height(e, n)});
    }
  auto at = [&](int i, int j) { return uint32_t(j * (cells + 1) + i); };
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i)
      g.triangles.insert(g.triangles.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
  return g;
}

inline void appendU32(std::vector<uint8_t>& out, uint32_t v) {
  uint8_t b[4];
  std::memcpy(b, &v, 4);
  out.insert(out.end(), b, b + 4);
}

// A GLB holding one triangle primitive: `points` are z up (shifted by
// -`offset` first) and written y up as glTF has them: (x, z, -y). With
// `draco` the primitive is KHR_draco_mesh_compression (positions not
// quantized, so they decode exactly).
inline std::vector<uint8_t> glbOf(const TestGrid& g, const glm::dvec3& offset = glm::dvec3(0.0), bool draco = false) {
  std::vector<float> xyz;
  for (const glm::dvec3& p : g.points) {
    const glm::dvec3 q = p - offset;
    xyz.insert(xyz.end(), {float(q.x), float(q.z), float(-q.y)});
  }
  std::vector<uint8_t> bin;
  Json gltf = {{"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", Json::array({{{"nodes", {0}}}})},
               {"nodes", Json::array({{{"mesh", 0}}})}};
  const size_t vertices = g.points.size();
  if (!draco) {
    bin.resize(xyz.size() * 4);
    std::memcpy(bin.data(), xyz.data(), bin.size());
    const size_t idxAt = bin.size();
    bin.resize(idxAt + g.triangles.size() * 4);
    std::memcpy(bin.data() + idxAt, g.triangles.data(), g.triangles.size() * 4);
    gltf["bufferViews"] = Json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", idxAt}},
                                       {{"buffer", 0}, {"byteOffset", idxAt}, {"byteLength", g.triangles.size() * 4}}});
    gltf["accessors"] = Json::array({{{"bufferView", 0}, {"componentType", 5126}, {"count", vertices}, {"type", "VEC3"}},
                                     {{"bufferView", 1}, {"componentType", 5125}, {"count", g.triangles.size()},
                                      {"type", "SCALAR"}}});
    gltf["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}})}}});
  } else {
    draco::TriangleSoupMeshBuilder b;
    b.Start(int(g.triangles.size() / 3));
    const int pos = b.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    for (size_t t = 0; t < g.triangles.size() / 3; ++t)
      b.SetAttributeValuesForFace(pos, draco::FaceIndex(uint32_t(t)), &xyz[g.triangles[t * 3] * 3],
                                  &xyz[g.triangles[t * 3 + 1] * 3], &xyz[g.triangles[t * 3 + 2] * 3]);
    std::unique_ptr<draco::Mesh> mesh = b.Finalize();
    draco::Encoder encoder;
    encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
    draco::EncoderBuffer buffer;
    if (!encoder.EncodeMeshToBuffer(*mesh, &buffer).ok()) return {};
    bin.assign(buffer.data(), buffer.data() + buffer.size());
    const int id = int(mesh->attribute(pos)->unique_id());
    gltf["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    gltf["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    gltf["bufferViews"] = Json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", bin.size()}}});
    gltf["accessors"] = Json::array({{{"componentType", 5126}, {"count", mesh->num_points()}, {"type", "VEC3"}},
                                     {{"componentType", 5125}, {"count", mesh->num_faces() * 3}, {"type", "SCALAR"}}});
    gltf["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", {{"POSITION", 0}}}, {"indices", 1},
        {"extensions", {{"KHR_draco_mesh_compression", {{"bufferView", 0}, {"attributes", {{"POSITION", id}}}}}}}}})}}});
  }
  while (bin.size() % 4) bin.push_back(0);
  gltf["buffers"] = Json::array({{{"byteLength", bin.size()}}});
  std::string json = gltf.dump();
  while (json.size() % 4) json.push_back(' ');
  std::vector<uint8_t> out;
  out.insert(out.end(), {'g', 'l', 'T', 'F'});
  appendU32(out, 2);
  appendU32(out, uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  appendU32(out, uint32_t(json.size()));
  out.insert(out.end(), {'J', 'S', 'O', 'N'});
  out.insert(out.end(), json.begin(), json.end());
  appendU32(out, uint32_t(bin.size()));
  out.insert(out.end(), {'B', 'I', 'N', 0});
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

// A b3dm around `glb` with RTC_CENTER `rtc` in its feature table.
inline std::vector<uint8_t> b3dmOf(const std::vector<uint8_t>& glb, const glm::dvec3& rtc) {
  std::string ft = Json{{"BATCH_LENGTH", 0}, {"RTC_CENTER", {rtc.x, rtc.y, rtc.z}}}.dump();
  while ((28 + ft.size()) % 8) ft.push_back(' ');
  std::vector<uint8_t> out;
  out.insert(out.end(), {'b', '3', 'd', 'm'});
  appendU32(out, 1);
  appendU32(out, uint32_t(28 + ft.size() + glb.size()));
  appendU32(out, uint32_t(ft.size()));
  appendU32(out, 0);
  appendU32(out, 0);
  appendU32(out, 0);
  out.insert(out.end(), ft.begin(), ft.end());
  out.insert(out.end(), glb.begin(), glb.end());
  return out;
}

// A binary subtree file of 3D Tiles 1.1 implicit tiling: "subt", version
// 1, the JSON and binary chunk lengths as 64-bit numbers, the JSON padded
// to 8 bytes with spaces, then the binary chunk padded with zeros.
inline std::vector<uint8_t> subtreeOf(const Json& json, std::vector<uint8_t> bin) {
  std::string text = json.dump();
  while (text.size() % 8) text.push_back(' ');
  while (bin.size() % 8) bin.push_back(0);
  std::vector<uint8_t> out = {'s', 'u', 'b', 't'};
  appendU32(out, 1);
  const uint64_t lengths[2] = {text.size(), bin.size()};
  const auto* l = reinterpret_cast<const uint8_t*>(lengths);
  out.insert(out.end(), l, l + 16);
  out.insert(out.end(), text.begin(), text.end());
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

inline void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}
inline void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

}  // namespace hs::test
