#include "foliage/instance.h"

#include <algorithm>
#include <cmath>

namespace hs::foliage {

namespace {
constexpr double kInvSqrt2 = 0.70710678118654752440;
constexpr double kRotScale = 1023.0;
}  // namespace

int64_t toSteps(double c) { return int64_t(std::llround(c * 1024.0)); }

CellKey cellOf(const glm::dvec3& w) {
  return {cellOfSteps(toSteps(w.x)), cellOfSteps(toSteps(w.y)), cellOfSteps(toSteps(w.z))};
}

glm::dvec3 quantized(const glm::dvec3& w) {
  return {double(toSteps(w.x)) * kStep, double(toSteps(w.y)) * kStep, double(toSteps(w.z)) * kStep};
}

uint32_t packRotation(const glm::dquat& qin) {
  glm::dquat q = qin;
  const double len = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  if (!(len > 0.0) || !std::isfinite(len)) return packRotation(glm::dquat(1, 0, 0, 0));
  double c[4] = {q.x / len, q.y / len, q.z / len, q.w / len};
  int largest = 0;
  for (int i = 1; i < 4; ++i)
    if (std::abs(c[i]) > std::abs(c[largest])) largest = i;
  const double sign = c[largest] < 0.0 ? -1.0 : 1.0;
  uint32_t bits = uint32_t(largest) << 30;
  int shift = 20;
  for (int i = 0; i < 4; ++i) {
    if (i == largest) continue;
    const double v = std::clamp(c[i] * sign, -kInvSqrt2, kInvSqrt2);
    const uint32_t k = uint32_t(std::lround((v + kInvSqrt2) / (2.0 * kInvSqrt2) * kRotScale));
    bits |= std::min<uint32_t>(k, 1023u) << shift;
    shift -= 10;
  }
  return bits;
}

glm::dquat unpackRotation(uint32_t bits) {
  const int largest = int(bits >> 30);
  double c[4];
  double sum = 0.0;
  int shift = 20;
  for (int i = 0; i < 4; ++i) {
    if (i == largest) continue;
    const double k = double((bits >> shift) & 1023u);
    c[i] = k / kRotScale * (2.0 * kInvSqrt2) - kInvSqrt2;
    sum += c[i] * c[i];
    shift -= 10;
  }
  c[largest] = std::sqrt(std::max(0.0, 1.0 - sum));
  const double len = std::sqrt(sum + c[largest] * c[largest]);
  return glm::dquat(c[3] / len, c[0] / len, c[1] / len, c[2] / len);  // (w, x, y, z)
}

uint16_t packScale(ScaleMode mode, const glm::dvec3& s) {
  auto lg = [](double v) { return std::log2(std::max(v, 1e-30)); };
  if (mode == ScaleMode::Uniform) {
    const double q = std::round((lg(s.x) + 8.0) * 4096.0);
    return uint16_t(std::clamp(q, 0.0, 65535.0));
  }
  const double h = std::clamp(std::round((lg(s.x) + 8.0) * 16.0), 0.0, 255.0);
  const double v = std::clamp(std::round((lg(s.z) + 8.0) * 16.0), 0.0, 255.0);
  return uint16_t((uint32_t(h) << 8) | uint32_t(v));
}

glm::dvec3 unpackScale(ScaleMode mode, uint16_t bits) {
  if (mode == ScaleMode::Uniform) return glm::dvec3(std::exp2(double(bits) / 4096.0 - 8.0));
  const double h = std::exp2(double(bits >> 8) / 16.0 - 8.0), v = std::exp2(double(bits & 255u) / 16.0 - 8.0);
  return {h, h, v};
}

PackedInstance pack(const Instance& in, ScaleMode mode, const CellKey& key) {
  PackedInstance p{};
  const int64_t g[3] = {toSteps(in.position.x), toSteps(in.position.y), toSteps(in.position.z)};
  const int32_t k[3] = {key.x, key.y, key.z};
  for (int a = 0; a < 3; ++a) {
    const int64_t local = g[a] - (int64_t(k[a]) << kCellShift);
    p.q[a] = uint16_t(std::clamp<int64_t>(local, 0, 65535));
  }
  p.scale = packScale(mode, in.scale);
  p.rot = packRotation(in.rotation);
  p.id = in.id;
  return p;
}

glm::dvec3 unpackPosition(const PackedInstance& p, const CellKey& key) {
  return {double((int64_t(key.x) << kCellShift) + p.q[0]) * kStep,
          double((int64_t(key.y) << kCellShift) + p.q[1]) * kStep,
          double((int64_t(key.z) << kCellShift) + p.q[2]) * kStep};
}

Instance unpack(const PackedInstance& p, ScaleMode mode, const CellKey& key) {
  Instance in;
  in.id = p.id;
  in.position = unpackPosition(p, key);
  in.rotation = unpackRotation(p.rot);
  in.scale = unpackScale(mode, p.scale);
  return in;
}

}  // namespace hs::foliage
