// OBJ + MTL + textures. Text written with the shortest exact decimal of
// each number (std::to_chars), so floats read back bit for bit and world
// coordinates keep every digit of the double.
#include <filesystem>

#include "mesh/export/export_geometry.h"

namespace hs::mesh::exporting {
namespace fs = std::filesystem;

namespace {

std::string materialName(const MeshData& mesh, int index) {
  if (index < 0 || index >= int(mesh.materials.size())) return "default";
  const std::string& n = mesh.materials[size_t(index)].name;
  std::string clean = n.empty() ? "material_" + std::to_string(index) : n;
  for (char& c : clean)
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') c = '_';
  return clean;
}

}  // namespace

bool writeObj(const MeshData& mesh, const Geometry& g, const std::string& path, const ExportOptions& o,
              PendingFiles& files, const Progress* progress, std::string& error) {
  const fs::path dir = fs::path(path).parent_path();
  const std::string stem = fs::path(path).stem().string();
  const bool hasUv = !g.uvs.empty(), hasNormals = !g.normals.empty();

  // Textures first: the MTL names their files.
  std::vector<std::string> textureFiles(mesh.textures.size());
  for (size_t t = 0; t < mesh.textures.size(); ++t) {
    bool used = false;
    for (const Material& m : mesh.materials) used |= m.diffuseTexture == int(t);
    if (!used) continue;
    std::string ext;
    const std::string bytes = textureFileBytes(mesh.textures[t], false, ext, error);
    if (bytes.empty()) {
      error = path + ": " + error;
      return false;
    }
    textureFiles[t] = stem + "_" + std::to_string(t) + ext;
    if (!files.add((dir / textureFiles[t]).string(), bytes, error)) return false;
  }

  std::string obj;
  obj.reserve(g.positions.size() * (hasUv ? 80 : 60) + g.indices.size() * 12);
  obj += "# Hybridscape mesh export\n";
  if (!o.comment.empty()) obj += "# " + o.comment + "\n";
  obj += std::string("# ") + (o.world ? "world coordinates" : "coordinates relative to the origin in " + stem +
                                                                  "_offset.xyz (when present)") +
         ", " + (o.zUp ? "Z up" : "Y up") + ", metres\n";
  const std::string mtlName = stem + ".mtl";
  obj += "mtllib " + mtlName + "\n";
  for (const glm::dvec3& p : g.positions) {
    obj += "v ";
    for (int i = 0; i < 3; ++i) {
      if (i) obj += ' ';
      if (g.world) appendNumber(obj, p[i]);
      else appendNumber(obj, float(p[i]));
    }
    obj += '\n';
  }
  reportProgress(progress, 0.3, "Writing vertices");
  for (const glm::vec2& t : g.uvs) {
    obj += "vt ";
    appendNumber(obj, t.x);
    obj += ' ';
    appendNumber(obj, 1.0f - t.y);  // OBJ's v points up
    obj += '\n';
  }
  for (const glm::vec3& n : g.normals) {
    obj += "vn ";
    for (int i = 0; i < 3; ++i) {
      if (i) obj += ' ';
      appendNumber(obj, n[i]);
    }
    obj += '\n';
  }
  if (isCancelled(progress)) return false;
  reportProgress(progress, 0.6, "Writing faces");
  auto corner = [&](uint32_t v) {
    const std::string i = std::to_string(v + 1);
    obj += i;
    if (hasUv || hasNormals) obj += '/' + (hasUv ? i : std::string());
    if (hasNormals) obj += '/' + i;
  };
  std::vector<Submesh> submeshes = mesh.submeshes;
  if (submeshes.empty()) submeshes.push_back({0, uint32_t(g.indices.size()), -1});
  for (const Submesh& s : submeshes) {
    obj += "usemtl " + materialName(mesh, s.material) + "\n";
    for (uint32_t k = s.firstIndex; k + 2 < s.firstIndex + s.indexCount && k + 2 < g.indices.size(); k += 3) {
      obj += "f ";
      corner(g.indices[k]);
      obj += ' ';
      corner(g.indices[k + 1]);
      obj += ' ';
      corner(g.indices[k + 2]);
      obj += '\n';
    }
  }

  // Kd is linear (as the OBJ reader takes it: docs/meshes.md).
  std::string mtl = "# Hybridscape mesh export\n";
  auto material = [&](const std::string& name, const glm::vec4& c, int texture) {
    mtl += "newmtl " + name + "\nKd ";
    for (int i = 0; i < 3; ++i) {
      if (i) mtl += ' ';
      appendNumber(mtl, c[i]);
    }
    mtl += "\nd ";
    appendNumber(mtl, c.a);
    mtl += '\n';
    if (texture >= 0 && texture < int(textureFiles.size()) && !textureFiles[size_t(texture)].empty())
      mtl += "map_Kd " + textureFiles[size_t(texture)] + "\n";
    mtl += '\n';
  };
  bool needDefault = false;
  for (const Submesh& s : submeshes) needDefault |= s.material < 0 || s.material >= int(mesh.materials.size());
  if (needDefault) material("default", Material{}.baseColor, -1);
  for (size_t m = 0; m < mesh.materials.size(); ++m)
    material(materialName(mesh, int(m)), mesh.materials[m].baseColor, mesh.materials[m].diffuseTexture);

  if (!files.add(path, obj, error)) return false;
  if (!files.add((dir / mtlName).string(), mtl, error)) return false;
  return true;
}

}  // namespace hs::mesh::exporting
