// Writes the small mesh files under tests/data/mesh/ that test_mesh_import
// reads: a textured quad as glTF binary (glb2, PNG texture embedded) and as
// FBX (ASCII, texture beside it), and the PNG itself; and the same FBX with
// the texture embedded (base64), which crashes Assimp 5.2.5's reader: the
// import isolation tests (tests/scene/test_import_isolation.cpp, test_cli_mesh)
// check that this costs a clear error, not the process.
//
// Why the FBX is ASCII with an external texture: Assimp 5.2.5 (Debian 12)
// cannot read back the binary FBX its own exporter writes ("FBX-Tokenize
// block offset is out of range"), and its reader crashes (double free) on the
// base64 texture its ASCII exporter embeds.
// Run once by hand; the outputs are committed (see tests/data/mesh/README.md):
//
//   cmake --build build --target make_mesh_fixtures
//   build/tests/mesh/make_mesh_fixtures tests/data/mesh
//
// Assimp's exporters build these, not our importer, so the test checks our
// importer against files it had no part in making.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <assimp/Exporter.hpp>
#include <assimp/material.h>
#include <assimp/scene.h>

#include "mesh_fixture_spec.h"

namespace fx = hs::test::fixture;
namespace fs = std::filesystem;

namespace {

bool writePng(const fs::path& path) {
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) return false;
  OIIO::ImageSpec spec(fx::kTexWidth, fx::kTexHeight, 4, OIIO::TypeDesc::UINT8);
  std::vector<uint8_t> pixels;
  for (const auto& t : fx::kTexels) pixels.insert(pixels.end(), t.begin(), t.end());
  return out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) &&
         out->close();
}

// The quad scene; the aiScene destructor frees everything allocated here.
// With `embed` the texture travels inside the file ("*0"), otherwise the
// material names the PNG beside it.
aiScene* buildScene(const std::vector<uint8_t>& png, bool embed) {
  auto* scene = new aiScene();
  scene->mRootNode = new aiNode("Root");
  auto* child = new aiNode("Quad");
  child->mTransformation = aiMatrix4x4();
  child->mTransformation.a4 = float(fx::kNodeTranslation[0]);
  child->mTransformation.b4 = float(fx::kNodeTranslation[1]);
  child->mTransformation.c4 = float(fx::kNodeTranslation[2]);
  child->mParent = scene->mRootNode;
  child->mNumMeshes = 1;
  child->mMeshes = new unsigned[1]{0};
  scene->mRootNode->mNumChildren = 1;
  scene->mRootNode->mChildren = new aiNode*[1]{child};

  auto* mesh = new aiMesh();
  mesh->mName = "Quad";
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  mesh->mNumVertices = 4;
  mesh->mVertices = new aiVector3D[4];
  mesh->mNormals = new aiVector3D[4];
  mesh->mTextureCoords[0] = new aiVector3D[4];
  mesh->mNumUVComponents[0] = 2;
  for (unsigned i = 0; i < 4; ++i) {
    const auto& p = fx::kQuadPositions[i];
    mesh->mVertices[i] = aiVector3D(p[0], p[1], p[2]);
    mesh->mNormals[i] = aiVector3D(0, 0, 1);
    mesh->mTextureCoords[0][i] = aiVector3D(fx::kQuadUvs[i][0], fx::kQuadUvs[i][1], 0);
  }
  mesh->mNumFaces = 2;
  mesh->mFaces = new aiFace[2];
  for (unsigned f = 0; f < 2; ++f) {
    mesh->mFaces[f].mNumIndices = 3;
    mesh->mFaces[f].mIndices = new unsigned[3];
    for (unsigned k = 0; k < 3; ++k) mesh->mFaces[f].mIndices[k] = fx::kQuadIndices[f * 3 + k];
  }
  mesh->mMaterialIndex = 0;
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh*[1]{mesh};

  auto* mat = new aiMaterial();
  const aiString name(fx::kMaterialName);
  mat->AddProperty(&name, AI_MATKEY_NAME);
  const aiColor4D colour(fx::kBaseColor[0], fx::kBaseColor[1], fx::kBaseColor[2], fx::kBaseColor[3]);
  mat->AddProperty(&colour, 1, AI_MATKEY_COLOR_DIFFUSE);
  mat->AddProperty(&colour, 1, AI_MATKEY_BASE_COLOR);
  const aiString texRef(embed ? "*0" : "checker_4x2.png");
  mat->AddProperty(&texRef, AI_MATKEY_TEXTURE(aiTextureType_DIFFUSE, 0));
  mat->AddProperty(&texRef, AI_MATKEY_TEXTURE(aiTextureType_BASE_COLOR, 0));
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial*[1]{mat};

  if (!embed) return scene;
  // Compressed embedded texture: mHeight 0, mWidth the byte count.
  auto* tex = new aiTexture();
  tex->mWidth = unsigned(png.size());
  tex->mHeight = 0;
  std::strncpy(tex->achFormatHint, "png", sizeof tex->achFormatHint - 1);
  tex->mFilename = aiString("checker_4x2.png");
  tex->pcData = new aiTexel[(png.size() + sizeof(aiTexel) - 1) / sizeof(aiTexel)];
  std::memcpy(tex->pcData, png.data(), png.size());
  scene->mNumTextures = 1;
  scene->mTextures = new aiTexture*[1]{tex};
  return scene;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_mesh_fixtures <output folder>\n");
    return 2;
  }
  const fs::path dir = argv[1];
  fs::create_directories(dir);
  const fs::path pngPath = dir / "checker_4x2.png";
  if (!writePng(pngPath)) {
    std::fprintf(stderr, "cannot write %s: %s\n", pngPath.c_str(), OIIO::geterror().c_str());
    return 1;
  }
  std::vector<uint8_t> png(size_t(fs::file_size(pngPath)));
  std::ifstream(pngPath, std::ios::binary).read(reinterpret_cast<char*>(png.data()), std::streamsize(png.size()));

  Assimp::Exporter exporter;
  int rc = 0;
  struct Output {
    const char* format;
    const char* file;
    bool embed;
  };
  for (const auto& [format, file, embed] : {Output{"glb2", "textured_quad.glb", true}, Output{"fbxa", "textured_quad.fbx", false},
                                            Output{"fbxa", "crashes_assimp_embedded_texture.fbx", true}}) {
    aiScene* scene = buildScene(png, embed);
    const fs::path out = dir / file;
    if (exporter.Export(scene, format, out.string()) != AI_SUCCESS) {
      std::fprintf(stderr, "%s: %s\n", out.c_str(), exporter.GetErrorString());
      rc = 1;
    } else {
      std::printf("wrote %s (%ju bytes)\n", out.c_str(), uintmax_t(fs::file_size(out)));
    }
    delete scene;
  }
  return rc;
}
