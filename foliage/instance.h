#pragma once
// One foliage instance, decoded (Instance: double world position, unit
// quaternion, scale) and packed (PackedInstance: 16 bytes, what cells hold
// in memory and in the file).
//
// Positions are quantised on one world grid of step 2^-10 m (0.977 mm):
// a world coordinate c is stored as the integer G = round(c * 1024), split
// into a cell index floor(G / 65536) and 16 bits inside the cell, so a cell
// is a 64 m cube (65536 steps) whose origin (cell index * 64) is exact in
// double. Decoding gives G / 1024 exactly, so the error per axis is at
// most half a step, 2^-11 m = 0.488 mm (0.846 mm in 3D), anywhere: at UTM
// coordinates (easting 5e5, northing 4.4e6: G < 2^33) as at the origin,
// because G and its halves are exact in double up to 2^53. Re-encoding a
// decoded instance gives the same bits (quantisation is idempotent).
//
// Rotation: the "smallest three" quaternion, 2 bits for the index of the
// largest component (made positive) and 10 bits for each other component
// in [-1/sqrt2, 1/sqrt2]: a stored component is off by at most e =
// sqrt2/1023/2 = 6.9e-4, the derived largest one (at least 1/2) by at most
// 3e, so the quaternion by at most sqrt(12) e and the rotation by at most
// 2 sqrt(12) e = 0.0048 rad (0.27 degrees: 9 cm at the top of a 20 m
// tree; measured 0.0043 rad over 1M random rotations, test_foliage_storage).
//
// Scale (16 bits): uniform types store log2(s) in steps of 1/4096 over
// [2^-8, 2^8) (relative error at most 2^(1/8192) - 1 = 0.0085%); xy_z types
// store log2 of the width and of the height scale in 8 bits each, steps of
// 1/16 over [2^-8, 2^8) (relative error at most 2.2%: a random scale a
// user never typed, the price of 16 bytes).
//
// The type is not in the record: a cell holds one run of records per
// (type, surface) pair (store.h), so the 16 bytes are position, rotation,
// scale and the stable id.
#include <cstdint>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "foliage/foliage_type.h"

namespace hs::foliage {

constexpr int kCellShift = 16;                    // steps per cell: 65536
constexpr double kStep = 1.0 / 1024.0;            // metres per step
constexpr double kCellSize = 65536.0 * kStep;     // 64 m
constexpr double kMaxPositionError = kStep / 2.0;  // per axis, metres

struct CellKey {
  int32_t x = 0, y = 0, z = 0;
  bool operator==(const CellKey&) const = default;
  auto operator<=>(const CellKey&) const = default;
  glm::dvec3 origin() const { return glm::dvec3(x, y, z) * kCellSize; }
};
struct CellKeyHash {
  size_t operator()(const CellKey& k) const {
    uint64_t h = uint64_t(uint32_t(k.x)) * 0x9E3779B97F4A7C15ull;
    h ^= uint64_t(uint32_t(k.y)) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= uint64_t(uint32_t(k.z)) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return size_t(h);
  }
};

// Where a type's instance stands on.
enum class Surface : uint8_t { Terrain = 0, Mesh = 1 };

struct Instance {
  uint32_t id = 0;
  uint16_t type = 0;
  Surface surface = Surface::Terrain;
  glm::dvec3 position{0.0};      // world, metres
  glm::dquat rotation{1, 0, 0, 0};
  glm::dvec3 scale{1.0};
};

#pragma pack(push, 1)
struct PackedInstance {
  uint16_t q[3];   // position in the cell, steps of 2^-10 m
  uint16_t scale;  // see above
  uint32_t rot;    // smallest three
  uint32_t id;
  bool operator==(const PackedInstance&) const = default;
};
#pragma pack(pop)
static_assert(sizeof(PackedInstance) == 16);

// Whole world steps of a coordinate, and the cell of a step.
int64_t toSteps(double c);
inline int32_t cellOfSteps(int64_t g) { return int32_t(g >> kCellShift); }
CellKey cellOf(const glm::dvec3& world);
// The world position quantisation stores (the centre of its step).
glm::dvec3 quantized(const glm::dvec3& world);

uint32_t packRotation(const glm::dquat& q);
glm::dquat unpackRotation(uint32_t bits);
uint16_t packScale(ScaleMode mode, const glm::dvec3& s);
glm::dvec3 unpackScale(ScaleMode mode, uint16_t bits);

// Packs an instance into cell `key` (which must be cellOf(position)).
PackedInstance pack(const Instance& in, ScaleMode mode, const CellKey& key);
// Everything but type and surface, which the cell's run holds.
Instance unpack(const PackedInstance& p, ScaleMode mode, const CellKey& key);
glm::dvec3 unpackPosition(const PackedInstance& p, const CellKey& key);

}  // namespace hs::foliage
