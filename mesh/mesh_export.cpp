#include "mesh/mesh_export.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "core/image_io.h"
#include "mesh/export/export_geometry.h"
#include "mesh/mesh_import.h"

namespace hs::mesh {
namespace fs = std::filesystem;

std::optional<ExportFormat> exportFormatFromPath(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".obj") return ExportFormat::Obj;
  if (ext == ".ply") return ExportFormat::Ply;
  if (ext == ".glb") return ExportFormat::Glb;
  return std::nullopt;
}

const char* exportFormatName(ExportFormat f) {
  return f == ExportFormat::Obj ? "obj" : f == ExportFormat::Ply ? "ply" : "glb";
}

namespace exporting {

Geometry placeGeometry(const MeshData& mesh, const ExportOptions& o, bool yUp) {
  Geometry g;
  g.world = o.world;
  const glm::dmat4& m = o.transform;
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(m)));
  const bool mirrored = glm::determinant(glm::dmat3(m)) < 0.0;
  auto axes = [yUp](glm::dvec3 p) { return yUp ? glm::dvec3(p.x, p.z, -p.y) : p; };
  const glm::dvec3 placedOrigin = glm::dvec3(m * glm::dvec4(mesh.origin, 1.0));
  g.origin = axes(placedOrigin);
  // reserve + push_back: resize() of glm vectors trips GCC 12's
  // -Wnull-dereference (a false positive in its inlined construction).
  g.positions.reserve(mesh.positions.size());
  for (const glm::vec3& p : mesh.positions) {
    const glm::dvec3 world = glm::dvec3(m * glm::dvec4(mesh.origin + glm::dvec3(p), 1.0));
    g.positions.push_back(axes(o.world ? world : world - placedOrigin));
  }
  if (mesh.normals.size() == mesh.positions.size()) {
    g.normals.reserve(mesh.normals.size());
    for (const glm::vec3& normal : mesh.normals) {
      const glm::dvec3 n = normalMatrix * glm::dvec3(normal);
      const double len = glm::length(n);
      g.normals.push_back(glm::vec3(axes(len > 0.0 ? n / len : glm::dvec3(0, 0, 1))));
    }
  }
  if (mesh.uvs.size() == mesh.positions.size()) g.uvs = mesh.uvs;
  g.indices = mesh.indices;
  if (mirrored)
    for (size_t t = 0; t + 2 < g.indices.size(); t += 3) std::swap(g.indices[t + 1], g.indices[t + 2]);
  return g;
}

PendingFiles::~PendingFiles() {
  std::error_code ec;
  for (const auto& [tmp, final] : files_) fs::remove(tmp, ec);
}

bool PendingFiles::add(const std::string& path, const std::string& bytes, std::string& error) {
  std::random_device rd;
  const std::string tmp = (fs::path(path).parent_path() / (".tmp-" + std::to_string(rd()) + "-" +
                                                           fs::path(path).filename().string()))
                              .string();
  std::ofstream out(tmp, std::ios::binary);
  if (!out) {
    error = path + ": cannot write here (" + fs::path(path).parent_path().string() + ")";
    return false;
  }
  files_.emplace_back(tmp, path);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  out.close();
  if (!out) {
    error = path + ": writing failed (disk full?)";
    return false;
  }
  return true;
}

bool PendingFiles::commit(std::vector<std::string>& written, std::string& error) {
  for (size_t i = 0; i < files_.size(); ++i) {
    std::error_code ec;
    fs::rename(files_[i].first, files_[i].second, ec);
    if (ec) {
      error = files_[i].second + ": cannot be written (" + ec.message() + ")";
      // Take back what this export already put in place.
      for (size_t j = 0; j < i; ++j) fs::remove(files_[j].second, ec);
      return false;
    }
    written.push_back(files_[i].second);
  }
  files_.clear();
  return true;
}

std::string textureFileBytes(const Texture& t, bool pngOrJpeg, std::string& extension, std::string& error) {
  const std::vector<uint8_t>& e = t.encoded;
  auto startsWith = [&e](std::initializer_list<uint8_t> sig) {
    return e.size() >= sig.size() && std::equal(sig.begin(), sig.end(), e.begin());
  };
  if (startsWith({0x89, 'P', 'N', 'G'})) extension = ".png";
  else if (startsWith({0xFF, 0xD8, 0xFF})) extension = ".jpg";
  else if (!pngOrJpeg && (startsWith({'I', 'I', 42, 0}) || startsWith({'M', 'M', 0, 42}))) extension = ".tif";
  else extension.clear();
  if (!extension.empty()) return std::string(e.begin(), e.end());
  // Pixels only (or an encoding other tools may not read): PNG through OpenImageIO.
  if (t.width <= 0 || t.height <= 0 || t.rgba.size() != size_t(t.width) * size_t(t.height) * 4) {
    error = "texture '" + t.name + "' has no pixels to write";
    return {};
  }
  extension = ".png";
  std::vector<uint8_t> buffer;
  const auto spec = image_io::Spec::of(t.width, t.height, 4, image_io::PixelType::UInt8);
  if (std::string why; !image_io::encode("png", spec, image_io::PixelType::UInt8, t.rgba.data(), buffer, why)) {
    error = "texture '" + t.name + "' could not be encoded as PNG: " + why;
    return {};
  }
  return std::string(buffer.begin(), buffer.end());
}

void appendNumber(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

void appendNumber(std::string& out, float v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

}  // namespace exporting

ExportResult exportMesh(const MeshData& mesh, const std::string& path, const ExportOptions& options,
                        const Progress* progress) {
  using namespace exporting;
  ExportResult r;
  if (mesh.triangleCount() == 0 || mesh.positions.empty()) {
    r.error = path + ": the mesh has no triangles to export";
    return r;
  }
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent)) {
    r.error = path + ": the folder " + parent.string() + " does not exist";
    return r;
  }
  const bool yUp = options.format == ExportFormat::Glb || !options.zUp;
  const Geometry g = placeGeometry(mesh, options, yUp);
  reportProgress(progress, 0.05, "Preparing");
  PendingFiles files;
  bool ok = false;
  switch (options.format) {
    case ExportFormat::Obj: ok = writeObj(mesh, g, path, options, files, progress, r.error); break;
    case ExportFormat::Ply: ok = writePly(mesh, g, path, options, files, progress, r.error); break;
    case ExportFormat::Glb: ok = writeGlb(mesh, g, path, options, files, progress, r.error, &r.quantizationError); break;
  }
  if (!ok) return r;
  // Relative positions: the placed origin beside the file as import's
  // offset sidecars hold it: in world axes (easting, northing, up), which
  // import adds after turning the file's axes to Z-up. For GLB too: its
  // node's translation would hold it only as a UTM offset that viewers
  // apply (that is --world); relative, the file is the mesh around zero.
  // A file that needs no offset (world positions, or an origin at zero)
  // writes none, but one left beside it by an earlier export to the same
  // name (of a mesh placed elsewhere) would move it on an import that reads
  // sidecars (`--origin auto`): that one is overwritten with a zero offset.
  const glm::dvec3 placedOrigin = glm::dvec3(options.transform * glm::dvec4(mesh.origin, 1.0));
  {
    const bool needed = !options.world && placedOrigin != glm::dvec3(0.0);
    const std::string sidecar = (parent / (fs::path(path).stem().string() + "_offset.xyz")).string();
    std::error_code ec;
    if (needed || fs::exists(sidecar, ec)) {
      std::string text;
      for (int i = 0; i < 3; ++i) {
        if (i) text += ' ';
        appendNumber(text, needed ? placedOrigin[i] : 0.0);
      }
      text += '\n';
      if (!files.add(sidecar, text, r.error)) return r;
    }
  }
  if (isCancelled(progress)) {
    r.error = path + ": the export was cancelled";
    return r;
  }
  if (!files.commit(r.written, r.error)) return r;
  std::stable_partition(r.written.begin(), r.written.end(), [&path](const std::string& f) { return f == path; });
  r.vertices = mesh.positions.size();
  r.triangles = mesh.triangleCount();
  r.origin = placedOrigin;
  if (options.format == ExportFormat::Ply) {
    // What PLY cannot hold is said, not only written into its header.
    std::vector<int> used, textures;
    for (const Submesh& sm : mesh.submeshes)
      if (sm.indexCount > 0 && std::find(used.begin(), used.end(), sm.material) == used.end()) {
        used.push_back(sm.material);
        const int t = sm.material >= 0 && size_t(sm.material) < mesh.materials.size()
                          ? mesh.materials[size_t(sm.material)].diffuseTexture
                          : -1;
        const bool listed = std::find(textures.begin(), textures.end(), t) != textures.end();
        if (t >= 0 && size_t(t) < mesh.textures.size() && !listed) textures.push_back(t);
      }
    if (used.size() > 1 || textures.size() > 1)
      r.warnings.push_back(path + ": PLY holds no materials and one texture: the faces of " +
                           std::to_string(used.size()) + " materials are written as one surface" +
                           (textures.size() > 1 ? ", with 1 of their " + std::to_string(textures.size()) + " textures"
                                                : std::string()) +
                           " (OBJ and GLB keep them)");
  }
  reportProgress(progress, 1.0, "Done");
  return r;
}

}  // namespace hs::mesh
