#pragma once
// What the committed files under tests/data/mesh/ contain, shared by their
// generator (make_mesh_fixtures.cpp) and by test_mesh_import, so the test
// checks the files against what they were made from, not against what our
// importer happens to read.
#include <array>
#include <cstdint>

namespace hs::test::fixture {

// A 4x2 RGBA8 checker, top row first (the order images are stored in).
constexpr int kTexWidth = 4;
constexpr int kTexHeight = 2;
constexpr std::array<std::array<uint8_t, 4>, kTexWidth * kTexHeight> kTexels = {{
    {255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}, {255, 255, 255, 255},   // top row
    {0, 0, 0, 255}, {255, 255, 0, 255}, {0, 255, 255, 255}, {255, 0, 255, 255},    // bottom row
}};

// One quad, 2 m wide and 1 m tall, standing in the file's XY plane (the
// files are Y-up), placed by its node at kNodeTranslation (file axes).
constexpr std::array<std::array<float, 3>, 4> kQuadPositions = {{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}}};
// Texture coordinates in the files' own convention (v = 0 at the image's
// bottom row, as OpenGL, FBX and Assimp's scene have it).
constexpr std::array<std::array<float, 2>, 4> kQuadUvs = {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
constexpr std::array<uint32_t, 6> kQuadIndices = {0, 1, 2, 0, 2, 3};
constexpr std::array<double, 3> kNodeTranslation = {10.0, 20.0, 30.0};

// The material's base colour (linear RGBA), next to its texture.
constexpr std::array<float, 4> kBaseColor = {0.25f, 0.5f, 0.75f, 1.0f};
constexpr const char* kMaterialName = "Checker";

}  // namespace hs::test::fixture
