#pragma once
// The geometry part of a serialised MeshData (origin, vertex arrays,
// indices, submeshes, materials), shared by the .hscene mesh blob
// (mesh_blob.cpp) and the import worker's result (import_wire.cpp); each
// writes its own header and textures around it. Templates over the two
// files' writers and readers (to memory, to a file): both offer
// pod/vec/str, readers with a field name for their error messages and `ok`.
#include <cstdint>

#include "mesh/mesh_data.h"

namespace hs::mesh {

template <class Writer>
void writeMeshGeometry(Writer& w, const mesh::MeshData& m) {
  w.pod(m.origin);
  w.vec(m.positions);
  w.vec(m.normals);
  w.vec(m.uvs);
  w.vec(m.indices);
  w.vec(m.submeshes);
  w.pod(uint64_t(m.materials.size()));
  for (const auto& mat : m.materials) {
    w.str(mat.name);
    w.pod(mat.baseColor);
    w.pod(int32_t(mat.diffuseTexture));
  }
}

template <class Reader>
void readMeshGeometry(Reader& r, mesh::MeshData& m) {
  m.origin = r.template pod<glm::dvec3>("origin");
  m.positions = r.template vec<glm::vec3>("positions");
  m.normals = r.template vec<glm::vec3>("normals");
  m.uvs = r.template vec<glm::vec2>("uvs");
  m.indices = r.template vec<uint32_t>("indices");
  m.submeshes = r.template vec<mesh::Submesh>("submeshes");
  const uint64_t nMaterials = r.template pod<uint64_t>("material count");
  for (uint64_t i = 0; r.ok && i < nMaterials; ++i) {
    mesh::Material mat;
    mat.name = r.str("material name");
    mat.baseColor = r.template pod<glm::vec4>("material colour");
    mat.diffuseTexture = r.template pod<int32_t>("material texture");
    m.materials.push_back(std::move(mat));
  }
}

}  // namespace hs::mesh
