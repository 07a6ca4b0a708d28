#include "mesh/assimp_importer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <unordered_map>

#include <assimp/Importer.hpp>
#include <assimp/ProgressHandler.hpp>
#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <glm/gtc/matrix_transform.hpp>

#include "mesh/assimp_io_guard.h"
#include "mesh/declared_counts.h"
#include "mesh/texture_decode.h"

namespace hs::mesh {
namespace {

class ProgressBridge : public Assimp::ProgressHandler {
 public:
  explicit ProgressBridge(const Progress* p) : progress_(p) {}
  bool Update(float percentage) override {
    if (percentage >= 0.0f) reportProgress(progress_, 0.8 * double(percentage), "Reading with Assimp");
    return !isCancelled(progress_);  // false makes Assimp abort
  }

 private:
  const Progress* progress_;
};

glm::dmat4 toGlm(const aiMatrix4x4& m) {
  // aiMatrix4x4 is row-major; glm is column-major.
  return glm::dmat4(m.a1, m.b1, m.c1, m.d1, m.a2, m.b2, m.c2, m.d2, m.a3, m.b3, m.c3, m.d3, m.a4,
                    m.b4, m.c4, m.d4);
}

// Which axis the file says is up; Y where it says nothing.
bool fileIsZUp(const aiScene& scene, const std::string& ext) {
  if (ext == ".gltf" || ext == ".glb") return false;  // Y-up by specification
  int32_t upAxis = 1;
  if (scene.mMetaData && scene.mMetaData->Get("UpAxis", upAxis)) return upAxis == 2;
  return false;
}

struct Builder {
  const aiScene& scene;
  MeshData& out;
  ImportReport& report;
  glm::dvec3 origin{0.0};
  bool haveOrigin = false;
  bool anyUv = false, allNormals = true;
  size_t skippedPrimitives = 0;
  // Assimp holds coordinates as 32-bit floats: the largest one read and the
  // spacing of floats there (in world metres), to say what precision was lost.
  double maxCoordinate = 0.0, floatSpacing = 0.0;

  void countUvsAndNormals(const aiNode& node) {
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      const aiMesh& m = *scene.mMeshes[node.mMeshes[i]];
      if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
      anyUv |= m.HasTextureCoords(0);
      allNormals &= m.HasNormals();
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c) countUvsAndNormals(*node.mChildren[c]);
  }

  void visit(const aiNode& node, const glm::dmat4& parent) {
    const glm::dmat4 world = parent * toGlm(node.mTransformation);
    const glm::dmat3 normalMat = glm::transpose(glm::inverse(glm::dmat3(world)));
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      const aiMesh& m = *scene.mMeshes[node.mMeshes[i]];
      if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) {
        skippedPrimitives += m.mNumFaces;
        continue;
      }
      const uint32_t base = uint32_t(out.positions.size());
      float meshMax = 0.0f;
      for (unsigned v = 0; v < m.mNumVertices; ++v) {
        const aiVector3D& p = m.mVertices[v];
        meshMax = std::max({meshMax, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
        const glm::dvec3 wp = glm::dvec3(world * glm::dvec4(p.x, p.y, p.z, 1.0));
        if (!haveOrigin && std::isfinite(wp.x) && std::isfinite(wp.y) && std::isfinite(wp.z)) {
          origin = glm::round(wp);
          haveOrigin = true;
        }
        out.positions.emplace_back(wp - origin);
        if (allNormals) {
          const aiVector3D& n = m.mNormals[v];
          const glm::dvec3 wn = normalMat * glm::dvec3(n.x, n.y, n.z);
          const double len = glm::length(wn);
          out.normals.emplace_back(len > 0.0 ? wn / len : glm::dvec3(0, 0, 1));
        }
        if (anyUv)
          out.uvs.push_back(m.HasTextureCoords(0)
                                ? glm::vec2(m.mTextureCoords[0][v].x, m.mTextureCoords[0][v].y)
                                : glm::vec2(0.0f));
      }
      if (std::isfinite(meshMax)) {
        const double scale = std::max({glm::length(world[0]), glm::length(world[1]), glm::length(world[2])});
        maxCoordinate = std::max(maxCoordinate, double(meshMax) * scale);
        floatSpacing = std::max(floatSpacing, double(std::nextafter(meshMax, INFINITY) - meshMax) * scale);
      }
      Submesh sm{uint32_t(out.indices.size()), 0, int(m.mMaterialIndex)};
      for (unsigned f = 0; f < m.mNumFaces; ++f) {
        const aiFace& face = m.mFaces[f];
        if (face.mNumIndices != 3) {
          ++skippedPrimitives;
          continue;
        }
        for (int k = 0; k < 3; ++k) out.indices.push_back(base + face.mIndices[k]);
      }
      sm.indexCount = uint32_t(out.indices.size()) - sm.firstIndex;
      report.trianglesIn += sm.indexCount / 3;
      if (sm.indexCount) out.submeshes.push_back(sm);
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c) visit(*node.mChildren[c], world);
  }
};

}  // namespace

bool assimpSupportsExtension(const std::string& ext) {
  Assimp::Importer importer;
  return importer.IsExtensionSupported(ext);
}

bool readWithAssimp(const std::string& path, const ImportOptions& options,
                    const Progress* progress, MeshData& out, ImportReport& report,
                    std::string& error) {
  Assimp::Importer importer;
  importer.SetProgressHandler(new ProgressBridge(progress));  // importer owns it
  importer.SetPropertyBool(AI_CONFIG_FBX_CONVERT_TO_M, true);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // No normal generation here: importMesh fills missing normals the same way
  // for every reader, and reports that it did.
  // GlobalScale applies the file's unit (FBX UnitScaleFactor): without it
  // Assimp 5.2 ignores AI_CONFIG_FBX_CONVERT_TO_M and a centimetre FBX comes
  // in 100 times too large. Formats without units keep a scale of 1.
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                         aiProcess_SortByPType | aiProcess_FlipUVs |
                         aiProcess_ValidateDataStructure | aiProcess_GlobalScale;
  const std::string ext = [&] {
    std::string e = std::filesystem::path(path).extension().string();
    for (auto& ch : e) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    return e;
  }();
  // Counts checked against the file's size before Assimp allocates what
  // they ask for; what the file declares is compared with what comes in.
  DeclaredCounts declared;
  if (!checkBeforeAssimp(path, declared, error)) return false;
  report.declaredTriangles = declared.triangles;
  report.declaredBy = declared.by;
  report.warnings.insert(report.warnings.end(), declared.warnings.begin(), declared.warnings.end());
  AssimpIoGuard guard;
  importer.SetIOHandler(guard.io());
  // Given back before the guard goes: the importer would delete it.
  struct Release {
    Assimp::Importer& importer;
    ~Release() { importer.SetIOHandler(nullptr); }
  } release{importer};
  const aiScene* scene = importer.ReadFile(path, flags);
  for (const auto& r : guard.refused()) report.warnings.push_back(path + ": Assimp asked for " + r);
  if (!scene) {
    if (isCancelled(progress)) {
      error = path + ": import cancelled";
      return false;
    }
    std::string why = importer.GetErrorString();
    if (why.empty()) why = "Assimp could not read it";
    // Assimp turns an allocation failure into this text, naming no place.
    if (why.find("bad_alloc") != std::string::npos)
      why = "ran out of memory while Assimp read it (" + why + "); the file asks for more than this process may use";
    if (!guard.refused().empty()) why += " (" + guard.refused().front() + ")";
    error = path + ": " + why;
    return false;
  }
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !scene->mRootNode) {
    error = path + ": the file holds no complete scene (truncated or not a mesh file)";
    return false;
  }

  bool zUp = options.up == UpAxis::Z || (options.up == UpAxis::Auto && fileIsZUp(*scene, ext));
  report.upAxisConverted = !zUp;
  // Y-up to Z-up: x stays, file y becomes z, file z becomes -y.
  const glm::dmat4 axis = zUp ? glm::dmat4(1.0)
                              : glm::dmat4(1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1);

  Builder b{*scene, out, report};
  b.countUvsAndNormals(*scene->mRootNode);
  b.visit(*scene->mRootNode, axis);
  out.origin = b.origin;
  report.verticesIn = out.positions.size();
  if (b.skippedPrimitives) {
    report.skippedLines += b.skippedPrimitives;
    report.warnings.push_back(path + ": " + std::to_string(b.skippedPrimitives) +
                              " line/point primitives were skipped (not triangles)");
  }
  if (out.indices.empty()) {
    error = path + ": no triangles to import";
    return false;
  }
  if (b.floatSpacing > 0.001) {
    char what[200];
    std::snprintf(what, sizeof what,
                  ": coordinates reach %.0f m; Assimp holds them as 32-bit floats, %.3g m apart "
                  "there, so finer detail was lost",
                  b.maxCoordinate, b.floatSpacing);
    report.warnings.push_back(path + what +
                              (ext == ".obj" ? " (the own OBJ reader keeps it: --reader obj)"
                                             : " (move the model near the origin where it was made)"));
  }

  // Materials and their diffuse textures (glTF calls it base colour).
  const std::string baseDir = std::filesystem::path(path).parent_path().string();
  std::unordered_map<std::string, int> textureByKey;
  reportProgress(progress, 0.85, "Loading textures");
  for (unsigned i = 0; i < scene->mNumMaterials; ++i) {
    const aiMaterial& am = *scene->mMaterials[i];
    Material m;
    m.name = am.GetName().C_Str();
    aiColor4D c;
    if (am.Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS || am.Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS)
      m.baseColor = glm::vec4(c.r, c.g, c.b, c.a);
    aiString texPath;
    bool hasTex = am.GetTexture(aiTextureType_DIFFUSE, 0, &texPath) == AI_SUCCESS ||
                  am.GetTexture(aiTextureType_BASE_COLOR, 0, &texPath) == AI_SUCCESS;
    if (hasTex && texPath.length > 0) {
      const std::string key = texPath.C_Str();
      if (auto it = textureByKey.find(key); it != textureByKey.end()) {
        m.diffuseTexture = it->second;
      } else {
        Texture tex;
        std::string texError, texNote;
        bool ok = false;
        if (const aiTexture* emb = scene->GetEmbeddedTexture(key.c_str())) {
          tex.name = key;
          if (emb->mHeight == 0) {  // compressed (PNG/JPEG bytes), mWidth is the byte count
            const auto* bytes = reinterpret_cast<const uint8_t*>(emb->pcData);
            ok = decodeTextureMemory({bytes, emb->mWidth}, emb->achFormatHint,
                                     path + ": embedded texture " + key, tex, texError, &texNote);
            if (ok) tex.encoded.assign(bytes, bytes + emb->mWidth);
          } else {  // raw BGRA texels
            tex.width = int(emb->mWidth);
            tex.height = int(emb->mHeight);
            tex.rgba.resize(size_t(tex.width) * tex.height * 4);
            for (size_t t = 0; t < size_t(tex.width) * tex.height; ++t) {
              const aiTexel& tx = emb->pcData[t];
              tex.rgba[t * 4 + 0] = tx.r;
              tex.rgba[t * 4 + 1] = tx.g;
              tex.rgba[t * 4 + 2] = tx.b;
              tex.rgba[t * 4 + 3] = tx.a;
            }
            ok = true;
          }
        } else {
          std::filesystem::path tp(key);
          if (tp.is_relative()) tp = std::filesystem::path(baseDir) / tp;
          ok = decodeTextureFile(tp.string(), tex, texError, &texNote);
          if (!ok && !std::filesystem::exists(tp)) {
            // Exporters often write absolute paths from the artist's machine:
            // look for the bare file name next to the mesh.
            const auto local = std::filesystem::path(baseDir) / tp.filename();
            std::string localError;
            if (decodeTextureFile(local.string(), tex, localError, &texNote)) ok = true;
          }
          tex.name = tp.filename().string();
        }
        if (ok) {
          if (!texNote.empty()) report.warnings.push_back(path + ": material '" + m.name + "': " + texNote);
          m.diffuseTexture = textureByKey[key] = int(out.textures.size());
          out.textures.push_back(std::move(tex));
        } else if (options.strictTextures) {
          error = path + ": material '" + m.name + "': " + texError;
          return false;
        } else {
          report.warnings.push_back(path + ": material '" + m.name + "': " + texError +
                                    " (the material is drawn untextured)");
        }
      }
    }
    out.materials.push_back(std::move(m));
  }
  return true;
}

}  // namespace hs::mesh
