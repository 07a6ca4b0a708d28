#include "mesh/mesh_import.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <new>

#include "mesh/assimp_importer.h"
#include "mesh/byte_source.h"
#include "mesh/mesh_sanitize.h"
#include "mesh/obj_reader.h"
#include "mesh/ply_reader.h"

namespace hs::mesh {
namespace {

ImportResult fail(ImportReport&& report, std::string error, const Progress* progress) {
  ImportResult r;
  r.cancelled = isCancelled(progress);
  r.error = std::move(error);
  r.report = std::move(report);
  return r;
}

// The georeferencing offset: only the double origin moves, so the float
// positions (and every test of the reader) are untouched.
bool applyGeoOffset(MeshData& mesh, ImportReport& report, const ImportOptions& options, std::string& error) {
  GeoOffset g;
  switch (options.geoOffsetMode) {
    case ImportOptions::GeoOffsetMode::None:
      return true;
    case ImportOptions::GeoOffsetMode::Manual:
      g.offset = options.geoOffset;
      g.source = "set by hand";
      break;
    case ImportOptions::GeoOffsetMode::File:
      if (!readGeoOffsetFile(options.geoOffsetFile, g, error)) return false;
      break;
    case ImportOptions::GeoOffsetMode::Auto: {
      std::vector<std::string> tried;
      const auto found = findGeoOffsetSidecar(report.file, &tried);
      for (const auto& t : tried)
        if (t.find(": used") == std::string::npos) report.warnings.push_back(t + " (offset file ignored)");
      if (!found) return true;
      g = *found;
      break;
    }
  }
  if (!g.warning.empty()) report.warnings.push_back(g.warning);
  mesh.origin += g.offset;
  report.geoOffset = g.offset;
  report.geoOffsetSource = g.source;
  report.geoOffsetCrs = g.crs;
  return true;
}

// "" when the triangles imported are those the file declares; otherwise a
// message saying how many of each and why they differ, as far as we know.
std::string declaredDifference(const ImportReport& report) {
  if (report.declaredBy.empty() || report.declaredTriangles == report.trianglesOut) return {};
  std::string why;
  auto add = [&](size_t n, const char* what) {
    if (n) why += (why.empty() ? "" : ", ") + std::to_string(n) + " " + what;
  };
  add(report.outOfRangeFaces, "with an index out of range");
  add(report.degenerateFaces, "repeating a vertex");
  add(report.nonFiniteVertices, "NaN/Inf vertices (their faces)");
  const bool more = report.trianglesOut > report.declaredTriangles;
  return report.file + ": the file declares " + std::to_string(report.declaredTriangles) + " triangles (" +
         report.declaredBy + ") but " + std::to_string(report.trianglesOut) + " were imported" +
         (more ? " (more than declared: the reader made some up or counts differently)"
               : why.empty() ? " (the reader dropped the rest without saying why)" : " (dropped: " + why + ")");
}

// Common tail of every reader: clean, fill normals, recentre, count.
ImportResult finish(MeshData&& mesh, ImportReport&& report, const ImportOptions& options,
                    const Progress* progress, std::chrono::steady_clock::time_point start) {
  ImportResult r;
  reportProgress(progress, 0.95, "Cleaning");
  // A Cancel pressed after the reader's last check (in its final stages, or
  // in a reader that does not check) still stops the import.
  if (isCancelled(progress)) {
    std::string error = report.file + ": import cancelled";
    return fail(std::move(report), std::move(error), progress);
  }
  sanitize(mesh, report);
  if (mesh.indices.empty()) {
    r.error = report.file + ": every face was invalid; nothing to import" +
              (report.warnings.empty() ? "" : " (" + report.warnings.front() + ")");
    r.report = std::move(report);
    return r;
  }
  if (mesh.normals.size() != mesh.positions.size()) {
    computeVertexNormals(mesh);
    report.normalsGenerated = true;
  }
  if (options.recenter) recenter(mesh);
  if (!applyGeoOffset(mesh, report, options, r.error)) {
    r.report = std::move(report);
    return r;
  }
  report.verticesOut = mesh.vertexCount();
  report.trianglesOut = mesh.triangleCount();
  if (std::string difference = declaredDifference(report); !difference.empty()) {
    if (options.strict) {
      r.error = difference + "; --strict refuses the import";
      r.report = std::move(report);
      return r;
    }
    report.warnings.push_back(std::move(difference));
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  reportProgress(progress, 1.0, "Done");
  r.mesh = std::move(mesh);
  r.report = std::move(report);
  return r;
}

// The reader the options pick, then finish(); `stage` says where it is for
// the out-of-memory message.
ImportResult readAndFinish(const std::string& path, const std::string& ext, bool useObj, bool usePly,
                           const ByteSource& file, const ImportOptions& options, const Progress* progress,
                           ImportReport&& report, std::chrono::steady_clock::time_point start, std::string& stage) {
  std::string error;
  MeshData mesh;
  if (usePly) {
    report.reader = "ply";
    const std::string baseDir = std::filesystem::path(path).parent_path().string();
    if (!readPly(file, baseDir, options, progress, mesh, report, error))
      return fail(std::move(report), std::move(error), progress);
  } else if (useObj) {
    report.reader = "obj";
    const std::string baseDir = std::filesystem::path(path).parent_path().string();
    if (!readObj(file, baseDir, options, progress, mesh, report, error))
      return fail(std::move(report), std::move(error), progress);
  } else {
    report.reader = "assimp";
    if (options.reader == Reader::Auto && !assimpSupportsExtension(ext))
      return fail(std::move(report),
                  path + ": '" + ext + "' is not a mesh format Hybridscape reads (use OBJ, FBX, PLY, glTF, DAE, 3DS, STL)",
                  progress);
    if (!readWithAssimp(path, options, progress, mesh, report, error))
      return fail(std::move(report), std::move(error), progress);
  }
  stage = "cleaning the " + std::to_string(mesh.triangleCount()) + " triangles read";
  return finish(std::move(mesh), std::move(report), options, progress, start);
}

}  // namespace

std::string lowerExtension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

std::vector<std::string> supportedExtensions() {
  return {".obj", ".fbx", ".ply", ".gltf", ".glb", ".dae", ".3ds", ".stl", ".off"};
}

ImportResult importObjFromMemory(std::string_view data, const std::string& name,
                                 const std::string& baseDir, const ImportOptions& options,
                                 const Progress* progress) {
  const auto start = std::chrono::steady_clock::now();
  ImportReport report;
  report.file = name;
  report.reader = "obj";
  MeshData mesh;
  std::string error;
  const ByteSource source(data, name);
  if (!readObj(source, baseDir, options, progress, mesh, report, error))
    return fail(std::move(report), std::move(error), progress);
  return finish(std::move(mesh), std::move(report), options, progress, start);
}

ImportResult importMesh(const std::string& path, const ImportOptions& options,
                        const Progress* progress) {
  const auto start = std::chrono::steady_clock::now();
  ImportReport report;
  report.file = path;
  const std::string ext = lowerExtension(path);

  // Check the path before any reader sees it, so the message is ours.
  ByteSource file;
  std::string error;
  if (!file.open(path, error)) return fail(std::move(report), std::move(error), progress);
  if (file.size() == 0) return fail(std::move(report), path + ": file is empty (0 bytes)", progress);

  const bool useObj =
      options.reader == Reader::Obj || (options.reader == Reader::Auto && ext == ".obj");
  const bool usePly = options.reader == Reader::Auto && ext == ".ply";
  // An allocation that fails (a count the checks let through, a memory
  // limit: tools/import_worker) becomes an error naming the file and the
  // stage it was in, never a bare std::bad_alloc.
  std::string stage = usePly   ? "reading it with the PLY reader"
                      : useObj ? "reading it with the OBJ reader"
                               : "reading it with Assimp";
  try {
    return readAndFinish(path, ext, useObj, usePly, file, options, progress, std::move(report), start, stage);
  } catch (const std::bad_alloc&) {
    ImportReport failed;
    failed.file = path;
    failed.reader = usePly ? "ply" : useObj ? "obj" : "assimp";
    return fail(std::move(failed),
                path + ": ran out of memory while " + stage + " (" + std::to_string(file.size()) +
                    " bytes); the file asks for more memory than this process may use",
                progress);
  }
}

}  // namespace hs::mesh
