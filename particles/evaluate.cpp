#include "particles/evaluate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

#include "core/content_hash.h"
#include "core/parallel.h"
#include "particles/noise.h"
#include "particles/rng.h"

namespace hs::particles {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = std::numbers::pi;
// A particle placed on a surface sits this far above it, so the next step's
// ray starts on the right side.
constexpr double kSkin = 1e-5;
// Contacts in one step beyond this: the particle is resting.
constexpr int kMaxContactsPerStep = 8;
// Candidates counted one by one for the cap's message; more are estimated.
constexpr uint64_t kMaxCounted = uint64_t(1) << 24;

// Two unit vectors perpendicular to unit `a` and to each other.
void basis(const glm::dvec3& a, glm::dvec3& b1, glm::dvec3& b2) {
  const glm::dvec3 h = std::abs(a.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  b1 = glm::normalize(glm::cross(h, a));
  b2 = glm::cross(a, b1);
}

ParticleRng rngOf(uint32_t seed, ParticleId id) {
  return ParticleRng{seed, id.stream ^ (uint32_t(id.index >> 32) * 0x9e3779b9U), uint32_t(id.index)};
}

}  // namespace

TriangleSurface::TriangleSurface(std::vector<glm::dvec3> corners) : corners_(std::move(corners)) {
  double total = 0.0;
  for (size_t i = 0; i + 2 < corners_.size(); i += 3) {
    total += 0.5 * glm::length(glm::cross(corners_[i + 1] - corners_[i], corners_[i + 2] - corners_[i]));
    cdf_.push_back(total);
  }
}

std::optional<std::pair<glm::dvec3, glm::dvec3>> TriangleSurface::box() const {
  if (corners_.empty()) return std::nullopt;
  glm::dvec3 lo = corners_.front(), hi = corners_.front();
  for (const glm::dvec3& c : corners_) lo = glm::min(lo, c), hi = glm::max(hi, c);
  return std::make_pair(lo, hi);
}

SurfacePoint TriangleSurface::sample(double u0, double u1, double u2) const {
  if (empty()) return {};
  const double target = u0 * cdf_.back();
  size_t t = size_t(std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin());
  t = std::min(t, cdf_.size() - 1);
  const glm::dvec3 &a = corners_[3 * t], &b = corners_[3 * t + 1], &c = corners_[3 * t + 2];
  const double s = std::sqrt(u1);
  SurfacePoint p;
  p.position = a * (1.0 - s) + b * (s * (1.0 - u2)) + c * (s * u2);
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double len = glm::length(n);
  p.normal = len > 0.0 ? n / len : glm::dvec3(0, 0, 1);
  return p;
}

Evaluator::Evaluator(const EmitterDesc& e, EvaluatorInputs inputs) : e_(e), in_(std::move(inputs)), spawn_(e) {
  const double len = glm::length(e_.direction);
  e_.direction = len > 0.0 ? e_.direction / len : glm::dvec3(0, 0, 1);
  forces_ = {e_.gravity, e_.drag, e_.wind};
  const std::string text = writeJson(emitterToJson(e_), -1);
  key_ = contentHash(text.data(), text.size());
  collide_ = e_.collision != CollisionMode::None && !in_.colliders.empty();
  replay_ = e_.turbulence > 0.0 || collide_;
}

std::optional<Evaluator> Evaluator::create(const EmitterDesc& e, EvaluatorInputs inputs, std::string& error) {
  const std::vector<std::string> problems = validate(e);
  if (!problems.empty()) {
    error = problems.front();
    return std::nullopt;
  }
  if (e.shape == Shape::Mesh && !inputs.surface) {
    error = "emitter '" + e.name + "', field 'mesh': the mesh '" + e.mesh + "' is missing (no surface to emit from)";
    return std::nullopt;
  }
  if (e.shape == Shape::Terrain && !inputs.ground) {
    error = "emitter '" + e.name + "', field 'shape': the shape is 'terrain' but no terrain was given to emit from";
    return std::nullopt;
  }
  if (e.turbulence > 0.0 || (e.collision != CollisionMode::None && !inputs.colliders.empty())) {
    const double steps = e.lifetimeMax / e.replayStep;
    if (steps > 1e7) {
      error = "emitter '" + e.name + "', field 'replay_step_s': a lifetime of " + formatNumber(e.lifetimeMax) +
              " s needs " + formatNumber(std::ceil(steps)) +
              " replay steps per particle (at most 10000000); use a longer step or a shorter lifetime";
      return std::nullopt;
    }
  }
  return Evaluator(e, std::move(inputs));
}

double Evaluator::birth(ParticleId id) const {
  if (id.stream == 0) return spawn_.birth(id.index);
  const size_t b = id.stream - 1;
  if (b >= e_.bursts.size() || id.index >= uint64_t(e_.bursts[b].count)) return kInf;
  return e_.bursts[b].t;
}

uint64_t Evaluator::candidates(double t) const {
  const double window = e_.lifetimeMax;
  uint64_t n = spawn_.bornBy(t) - spawn_.bornBy(t - window);
  for (const Burst& b : e_.bursts)
    if (b.t <= t && t - b.t < window) n += uint64_t(b.count);
  return n;
}

uint64_t Evaluator::liveCount(double t, bool* estimated) const {
  const Census c = census(t, 0, nullptr);
  if (estimated) *estimated = c.estimated;
  return c.live;
}

SpawnValues spawnValues(const EmitterDesc& e) {
  SpawnValues v;
  v.speedMin = e.speedMin, v.speedMax = e.speedMax, v.sizeMin = e.sizeMin, v.sizeMax = e.sizeMax;
  v.rotationMinDeg = e.rotationMinDeg, v.rotationMaxDeg = e.rotationMaxDeg;
  v.spinMinDegPerS = e.spinMinDegPerS, v.spinMaxDegPerS = e.spinMaxDegPerS;
  v.spreadDeg = e.spreadDeg, v.coneAngleDeg = e.coneAngleDeg, v.radius = e.radius;
  v.direction = e.direction, v.boxHalf = e.boxHalf;
  return v;
}

namespace {

// The one table of spawn values: each key's member(s) of SpawnValues and
// its declaration (for the range a track's value is held to).
struct SpawnMember {
  std::string key;
  double SpawnValues::*lo = nullptr;        // a number, or a MIN,MAX pair's MIN
  double SpawnValues::*hi = nullptr;        // a pair's MAX
  glm::dvec3 SpawnValues::*vec = nullptr;   // direction, box_half_m
  const ParamDecl* decl = nullptr;
  size_t count() const { return vec ? 3 : 1; }
};

const std::vector<SpawnMember>& spawnMembers() {
  using V = SpawnValues;
  static const std::vector<SpawnMember> table = [] {
    std::vector<SpawnMember> t = {{"speed_m_per_s", &V::speedMin, &V::speedMax},
                                  {"size_m", &V::sizeMin, &V::sizeMax},
                                  {"rotation_deg", &V::rotationMinDeg, &V::rotationMaxDeg},
                                  {"spin_deg_per_s", &V::spinMinDegPerS, &V::spinMaxDegPerS},
                                  {"spread_deg", &V::spreadDeg},
                                  {"cone_angle_deg", &V::coneAngleDeg},
                                  {"radius_m", &V::radius},
                                  {"direction", nullptr, nullptr, &V::direction},
                                  {"box_half_m", nullptr, nullptr, &V::boxHalf}};
    for (SpawnMember& m : t) m.decl = &paramIn(emitterParamDecls(), m.key);
    return t;
  }();
  return table;
}

}  // namespace

const std::vector<std::string>& spawnKeys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k;
    for (const SpawnMember& m : spawnMembers()) k.push_back(m.key);
    return k;
  }();
  return keys;
}

int spawnSlot(std::string_view key) {
  const std::vector<SpawnMember>& t = spawnMembers();
  for (size_t i = 0; i < t.size(); ++i)
    if (t[i].key == key) return int(i);
  return -1;
}

bool isSpawnKey(std::string_view key) { return spawnSlot(key) >= 0; }

size_t spawnValueCount(std::string_view key) {
  const int slot = spawnSlot(key);
  return slot < 0 ? 0 : spawnMembers()[size_t(slot)].count();
}

std::vector<double> spawnValue(const SpawnValues& v, std::string_view key) {
  const int slot = spawnSlot(key);
  if (slot < 0) return {};
  const SpawnMember& m = spawnMembers()[size_t(slot)];
  if (m.vec) return {(v.*m.vec).x, (v.*m.vec).y, (v.*m.vec).z};
  if (m.hi) return {0.5 * (v.*m.lo + v.*m.hi)};
  return {v.*m.lo};
}

void setSpawnValue(SpawnValues& v, int slot, const double* value) {
  const SpawnMember& m = spawnMembers()[size_t(slot)];
  const ParamDecl& d = *m.decl;
  auto held = [&](double x) { return std::clamp(std::isfinite(x) ? x : d.min, d.min, d.max); };
  if (m.vec) {
    const glm::dvec3 x{held(value[0]), held(value[1]), held(value[2])};
    if (m.vec != &SpawnValues::direction) {
      v.*m.vec = x;
    } else if (const double len = glm::length(x); len > 0.0) {
      v.direction = x / len;  // a zero direction keeps the emitter's
    }
  } else if (m.hi) {
    // A MIN,MAX pair: the track moves its centre and keeps its half-width.
    const double half = 0.5 * (v.*m.hi - v.*m.lo), c = held(value[0]);
    v.*m.lo = std::clamp(c - half, d.min, d.max);
    v.*m.hi = std::clamp(c + half, d.min, d.max);
  } else {
    v.*m.lo = held(value[0]);
  }
}

bool setSpawnValue(SpawnValues& v, std::string_view key, const double* value, size_t count) {
  const int slot = spawnSlot(key);
  if (slot < 0 || count != spawnMembers()[size_t(slot)].count()) return false;
  setSpawnValue(v, slot, value);
  return true;
}

ParticleStart Evaluator::start(ParticleId id) const { return startAt(id, birth(id)); }

ParticleStart Evaluator::startAt(ParticleId id, double birthTime) const {
  const ParticleRng r = rngOf(e_.seed, id);
  // The emitter's spawn values, or those keyed at the birth time.
  SpawnValues sv = spawnValues(e_);
  if (in_.spawnAt) in_.spawnAt(birthTime, sv);
  ParticleStart s;
  s.birth = birthTime;
  s.lifetime = r.range(Attr::Lifetime, e_.lifetimeMin, e_.lifetimeMax);
  s.size = r.range(Attr::Size, sv.sizeMin, sv.sizeMax);
  s.rotationDeg = r.range(Attr::Rotation, sv.rotationMinDeg, sv.rotationMaxDeg);
  s.spinDegPerS = r.range(Attr::Spin, sv.spinMinDegPerS, sv.spinMaxDegPerS);

  const double a = r.unit(Attr::ShapeA), b = r.unit(Attr::ShapeB), c = r.unit(Attr::ShapeC);
  const glm::dvec3 axis = sv.direction;
  // Where the emitter was at the birth (world space), relative to where it is.
  const bool moved = e_.space == Space::World && in_.originAt;
  const glm::dvec3 bornAt = moved ? in_.originAt(birthTime) : e_.origin;
  glm::dvec3 b1, b2;
  basis(axis, b1, b2);
  glm::dvec3 pos(0.0), normal = axis, base = axis;
  switch (e_.shape) {
    case Shape::Point: break;
    case Shape::Box: pos = (2.0 * glm::dvec3(a, b, c) - 1.0) * sv.boxHalf; break;
    case Shape::Sphere: {
      const double z = 2.0 * a - 1.0, phi = 2.0 * kPi * b, rr = std::sqrt(std::max(0.0, 1.0 - z * z));
      normal = {rr * std::cos(phi), rr * std::sin(phi), z};
      pos = normal * (sv.radius * (e_.surfaceOnly ? 1.0 : std::cbrt(c)));
      break;
    }
    case Shape::Disc:
    case Shape::Cone: {
      const double rho = e_.surfaceOnly ? 1.0 : std::sqrt(a), phi = 2.0 * kPi * b;
      const glm::dvec3 radial = std::cos(phi) * b1 + std::sin(phi) * b2;
      pos = radial * (sv.radius * rho);
      if (e_.shape == Shape::Cone) {
        // Unity's cone: the direction leans out in proportion to the distance from the axis.
        const double lean = sv.coneAngleDeg * kPi / 180.0 * rho;
        base = normal = std::cos(lean) * axis + std::sin(lean) * radial;
      }
      break;
    }
    case Shape::Terrain: {
      const double wx = bornAt.x + (2.0 * a - 1.0) * sv.boxHalf.x, wy = bornAt.y + (2.0 * b - 1.0) * sv.boxHalf.y;
      const double ground = in_.ground ? in_.ground->height(wx, wy) : bornAt.z;
      // Relative coordinates formed from world ones in double (exact for the x, y offsets).
      pos = {wx - e_.origin.x, wy - e_.origin.y, ground - e_.origin.z + c * sv.boxHalf.z};
      normal = in_.ground ? in_.ground->normal(wx, wy) : axis;
      break;
    }
    case Shape::Mesh: {
      const SurfacePoint p = in_.surface ? in_.surface->sample(a, b, c) : SurfacePoint{};
      pos = p.position;
      normal = p.normal;
      break;
    }
  }
  // The terrain shape is placed in world coordinates already; the mesh
  // shape's surface is where its entity is now.
  if (moved && e_.shape != Shape::Terrain && e_.shape != Shape::Mesh) pos += bornAt - e_.origin;
  if (e_.alongNormal) base = normal;
  glm::dvec3 dir = base;
  if (sv.spreadDeg > 0.0) {
    const double cosMax = std::cos(sv.spreadDeg * kPi / 180.0);
    const double ct = 1.0 - r.unit(Attr::SpreadA) * (1.0 - cosMax), st = std::sqrt(std::max(0.0, 1.0 - ct * ct));
    const double phi = 2.0 * kPi * r.unit(Attr::SpreadB);
    glm::dvec3 c1, c2;
    basis(base, c1, c2);
    dir = ct * base + st * (std::cos(phi) * c1 + std::sin(phi) * c2);
  }
  s.state.x = pos;
  s.state.v = dir * r.range(Attr::Speed, sv.speedMin, sv.speedMax);
  return s;
}

void Evaluator::advance(ReplayState& s, double t0, double tau) const {
  if (s.fate != Fate::Flying || !(tau > 0.0)) return;
  Forces f = forces_;
  if (e_.turbulence > 0.0) {
    // Second order: the turbulence at the step's predicted midpoint.
    const glm::dvec3 mid = exactMotionKeyed(s.k, f, e_.windKeys, t0, 0.5 * tau).x;
    f.gravity += turbulenceAt(mid, t0 + 0.5 * tau, e_.turbulence, e_.turbulenceFrequency, e_.turbulenceEvolution,
                              e_.seed);
  }
  double remaining = tau, now = t0;
  for (int contact = 0; contact <= kMaxContactsPerStep; ++contact) {
    const Kinematics next = exactMotionKeyed(s.k, f, e_.windKeys, now, remaining);
    if (!collide_) {
      s.k = next;
      return;
    }
    const std::optional<Hit> hit = nearestHit(in_.colliders, e_.origin + s.k.x, e_.origin + next.x);
    if (!hit) {
      s.k = next;
      return;
    }
    if (contact == kMaxContactsPerStep) break;
    // The hit time on the exact trajectory: where it crosses the tangent plane at the hit.
    const glm::dvec3 n = hit->normal, P = hit->point - e_.origin;
    auto dist = [&](double x) { return glm::dot(exactMotionKeyed(s.k, f, e_.windKeys, now, x).x - P, n); };
    double lo = 0.0, hi = remaining;
    if (dist(0.0) <= 0.0) {
      hi = 0.0;
    } else {
      for (int it = 0; it < 64 && hi - lo > 1e-12 * remaining; ++it) {
        const double m = 0.5 * (lo + hi);
        (dist(m) > 0.0 ? lo : hi) = m;
      }
    }
    Kinematics c = exactMotionKeyed(s.k, f, e_.windKeys, now, hi);
    c.x += n * (kSkin - glm::dot(c.x - P, n));
    switch (e_.collision) {
      case CollisionMode::None: break;
      case CollisionMode::Kill:
        s.k = c;
        s.fate = Fate::Killed;
        s.fateTime = now + hi;
        return;
      case CollisionMode::Stick:
        s.k = {c.x, glm::dvec3(0.0)};
        s.fate = Fate::Resting;
        s.fateTime = now + hi;
        return;
      case CollisionMode::Bounce: {
        const double vn = glm::dot(c.v, n);
        if (vn < 0.0) {
          const glm::dvec3 vt = c.v - vn * n;
          const double out = -e_.restitution * vn;
          if (out < e_.restSpeed) {
            s.k = {c.x, glm::dvec3(0.0)};
            s.fate = Fate::Resting;
            s.fateTime = now + hi;
            return;
          }
          c.v = vt * (1.0 - e_.friction) + out * n;
        }
        s.k = c;
        remaining -= hi;
        now += hi;
        if (!(remaining > 0.0)) return;
        break;
      }
    }
  }
  // Contact after contact inside one step: resting contact.
  s.k.v = glm::dvec3(0.0);
  s.fate = Fate::Resting;
  s.fateTime = now;
}

ReplayState Evaluator::replayTo(const ReplayState& from, double birthTime, double t, uint64_t& stepsTaken,
                                ReplayState* atLastWholeStep) const {
  const double h = e_.replayStep;
  const double age = std::max(0.0, t - birthTime);
  const uint64_t n = uint64_t(std::floor(age / h));
  ReplayState s = from;
  while (s.step < n) {
    if (s.fate != Fate::Flying) {
      s.step = n;
      break;
    }
    advance(s, birthTime + double(s.step) * h, h);
    ++s.step;
    ++stepsTaken;
  }
  if (atLastWholeStep) *atLastWholeStep = s;
  const double rem = age - double(n) * h;
  if (rem > 0.0) advance(s, birthTime + double(n) * h, rem);
  return s;
}

Particle Evaluator::finish(ParticleId id, const ParticleStart& st, const ReplayState& rs, double t) const {
  Particle p;
  p.id = id;
  p.birth = st.birth;
  p.lifetime = st.lifetime;
  p.age = t - st.birth;
  p.position = rs.k.x;
  p.velocity = rs.k.v;
  p.fate = rs.fate;
  const bool killed = rs.fate == Fate::Killed && rs.fateTime <= t;
  p.alive = p.age >= 0.0 && p.age < st.lifetime && !killed;
  const double life = st.lifetime > 0.0 ? std::clamp(p.age / st.lifetime, 0.0, 1.0) : 0.0;
  p.size = st.size * e_.sizeOverLife.eval(life, 1.0);
  p.colour = e_.colourOverLife.eval(life);
  p.rotationDeg = st.rotationDeg + st.spinDegPerS * std::max(0.0, p.age);
  p.frame = std::min(e_.flipbookFrames - 1, int(life * double(e_.flipbookFrames)));
  return p;
}

Particle Evaluator::particle(ParticleId id, double t, ReplayCache* cache) const {
  const ParticleStart st = start(id);
  if (!(st.birth <= t)) {
    Particle p;
    p.id = id;
    p.birth = st.birth;
    p.lifetime = st.lifetime;
    return p;
  }
  ReplayState rs;
  rs.k = st.state;
  if (!replay_) {
    rs.k = exactMotionKeyed(st.state, forces_, e_.windKeys, st.birth, t - st.birth);
    return finish(id, st, rs, t);
  }
  if (cache && cache->emitterKey_ != key_) {
    cache->clear();
    cache->emitterKey_ = key_;
  }
  ReplayState from = rs;
  const ReplayCache::Key key{id.stream, id.index};
  if (cache) {
    const auto it = cache->entries_.find(key);
    const uint64_t n = uint64_t(std::floor(std::max(0.0, t - st.birth) / e_.replayStep));
    if (it != cache->entries_.end() && it->second.state.step <= n) {
      from = it->second.state;
      ++cache->hits;
    } else {
      ++cache->misses;
    }
  }
  uint64_t steps = 0;
  ReplayState whole;
  rs = replayTo(from, st.birth, t, steps, &whole);
  if (cache) cache->entries_[key] = {whole, cache->frameCounter_};
  return finish(id, st, rs, t);
}

Evaluator::Census Evaluator::census(double t, uint64_t cap, std::vector<Candidate>* keptOut) const {
  Census out;
  const double window = e_.lifetimeMax;
  // Candidates in birth order: the rate's stream is already in order;
  // bursts (one birth time each) slot in before rate particles of the same time.
  std::vector<Candidate> none;
  std::vector<Candidate>& kept = keptOut ? *keptOut : none;
  std::vector<size_t> burstOrder;
  for (size_t b = 0; b < e_.bursts.size(); ++b)
    if (e_.bursts[b].count > 0 && e_.bursts[b].t <= t && t - e_.bursts[b].t < window) burstOrder.push_back(b);
  std::stable_sort(burstOrder.begin(), burstOrder.end(),
                   [&](size_t x, size_t y) { return e_.bursts[x].t < e_.bursts[y].t; });
  uint64_t counted = 0;
  bool& estimated = out.estimated;
  // Visits one candidate born at `b`; false once counting stops. Only the
  // lifetime is drawn here; the rest of the start is made in parallel below.
  auto visit = [&](ParticleId id, double b) {
    if (kept.size() < cap) {
      const double life = rngOf(e_.seed, id).range(Attr::Lifetime, e_.lifetimeMin, e_.lifetimeMax);
      const double age = t - b;
      if (age >= 0.0 && age < life) {
        ++out.live;
        kept.push_back({id, ParticleStart{.birth = b}});
      }
      return true;
    }
    if (counted >= kMaxCounted) return false;
    ++counted;
    const double life = rngOf(e_.seed, id).range(Attr::Lifetime, e_.lifetimeMin, e_.lifetimeMax);
    if (t - b < life) ++out.live;
    return true;
  };
  // The rate's candidates: born in (t - lifetimeMax, t].
  const uint64_t k0 = spawn_.bornBy(t - window), k1 = spawn_.bornBy(t);
  uint64_t k = k0;
  size_t nb = 0;
  {
    uint64_t expect = k1 - k0;
    for (size_t b : burstOrder) expect += uint64_t(e_.bursts[b].count);
    kept.reserve(size_t(std::min({expect, cap, uint64_t(1) << 22})));
  }
  bool going = true;
  uint64_t burstResume = 0;  // the interrupted burst's next index
  while (going && (k < k1 || nb < burstOrder.size())) {
    const double tk = k < k1 ? spawn_.birth(k) : kInf;
    if (nb < burstOrder.size() && e_.bursts[burstOrder[nb]].t <= tk) {
      const Burst& b = e_.bursts[burstOrder[nb]];
      uint64_t i = 0;
      for (; i < uint64_t(b.count) && going; ++i) going = visit({uint32_t(burstOrder[nb] + 1), i}, b.t);
      if (!going) {
        burstResume = i - 1;
        break;
      }
      ++nb;
      continue;
    }
    going = visit({0, k}, tk);
    if (!going) break;
    ++k;
  }
  if (!going) {
    // Too many to count one by one: the rest by the survival of an even
    // sample of them (4096 per stream), scaled to their number.
    estimated = true;
    auto sampled = [&](uint32_t stream, uint64_t from, uint64_t to, auto birthOf) {
      const uint64_t total = to - from, m = std::min<uint64_t>(total, 4096);
      if (m == 0) return uint64_t(0);
      uint64_t alive = 0;
      for (uint64_t j = 0; j < m; ++j) {
        const uint64_t idx = from + j * total / m;
        const ParticleId id{stream, idx};
        alive += t - birthOf(idx) < rngOf(e_.seed, id).range(Attr::Lifetime, e_.lifetimeMin, e_.lifetimeMax);
      }
      return uint64_t(std::llround(double(alive) * double(total) / double(m)));
    };
    for (size_t q = nb; q < burstOrder.size(); ++q) {
      const Burst& b = e_.bursts[burstOrder[q]];
      out.live += sampled(uint32_t(burstOrder[q] + 1), q == nb ? burstResume : 0, uint64_t(b.count),
                          [&](uint64_t) { return b.t; });
    }
    out.live += sampled(0, k, k1, [&](uint64_t idx) { return spawn_.birth(idx); });
  }
  return out;
}

Frame Evaluator::frame(double t, ReplayCache* cache, int threads) const {
  Frame out;
  out.t = t;
  const uint64_t cap = uint64_t(e_.maxLive);
  std::vector<Candidate> kept;
  const Census counts = census(t, cap, &kept);
  out.live = counts.live;
  const bool estimated = counts.estimated;
  out.leftOut = out.live > kept.size() ? out.live - kept.size() : 0;
  out.leftOutExact = !estimated;
  if (out.leftOut > 0) {
    out.message = "emitter '" + e_.name + "': " + std::to_string(out.live) + (estimated ? " (estimated)" : "") +
                  " live particles at t = " + formatNumber(t) + " s exceed max_live " + std::to_string(cap) + "; " +
                  std::to_string(out.leftOut) + " left out (the oldest " + std::to_string(cap) + " are kept)";
  }

  // Evaluate the kept ones: cache lookups in order, the work in parallel,
  // the cache updated in order.
  const size_t n = kept.size();
  parallelFor(int64_t(n), threads, 1024, [&](int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i) kept[size_t(i)].start = startAt(kept[size_t(i)].id, kept[size_t(i)].start.birth);
  });
  std::vector<Particle>& result = out.particles;
  result.resize(n);
  if (replay_) {
    if (cache && cache->emitterKey_ != key_) {
      cache->clear();
      cache->emitterKey_ = key_;
    }
    if (cache) ++cache->frameCounter_;
    std::vector<ReplayState> from(n), whole(n);
    std::vector<uint64_t> steps(n, 0);
    for (size_t i = 0; i < n; ++i) {
      from[i].k = kept[i].start.state;
      if (!cache) continue;
      const auto it = cache->entries_.find({kept[i].id.stream, kept[i].id.index});
      const uint64_t want = uint64_t(std::floor(std::max(0.0, t - kept[i].start.birth) / e_.replayStep));
      if (it != cache->entries_.end() && it->second.state.step <= want) {
        from[i] = it->second.state;
        ++cache->hits;
      } else {
        ++cache->misses;
      }
    }
    parallelFor(int64_t(n), threads, 64, [&](int64_t b, int64_t e) {
      for (int64_t i = b; i < e; ++i) {
        const ReplayState rs = replayTo(from[size_t(i)], kept[size_t(i)].start.birth, t, steps[size_t(i)],
                                        &whole[size_t(i)]);
        result[size_t(i)] = finish(kept[size_t(i)].id, kept[size_t(i)].start, rs, t);
      }
    });
    for (size_t i = 0; i < n; ++i) {
      out.replaySteps += steps[i];
      if (cache) cache->entries_[{kept[i].id.stream, kept[i].id.index}] = {whole[i], cache->frameCounter_};
    }
    if (cache) {
      // Drop the particles this frame did not touch (dead, or scrubbed away from).
      std::erase_if(cache->entries_, [&](const auto& kv) { return kv.second.frame != cache->frameCounter_; });
    }
  } else {
    parallelFor(int64_t(n), threads, 1024, [&](int64_t b, int64_t e) {
      for (int64_t i = b; i < e; ++i) {
        const Candidate& c = kept[size_t(i)];
        ReplayState rs;
        rs.k = exactMotionKeyed(c.start.state, forces_, e_.windKeys, c.start.birth, t - c.start.birth);
        result[size_t(i)] = finish(c.id, c.start, rs, t);
      }
    });
  }
  out.killed = uint64_t(std::erase_if(result, [](const Particle& p) { return !p.alive; }));
  return out;
}

std::vector<PackedParticle> packFrame(const Frame& frame, const glm::dvec3& emitterOrigin, const glm::dvec3& relativeTo,
                                      uint32_t seed) {
  const glm::dvec3 offset = emitterOrigin - relativeTo;  // double, before any float
  std::vector<PackedParticle> out(frame.particles.size());
  for (size_t i = 0; i < out.size(); ++i) {
    const Particle& p = frame.particles[i];
    PackedParticle& q = out[i];
    const glm::dvec3 x = offset + p.position;
    for (int c = 0; c < 3; ++c) {
      q.position[c] = float(x[c]);
      q.velocity[c] = float(p.velocity[c]);
    }
    for (int c = 0; c < 4; ++c) q.colour[c] = float(p.colour[c]);
    q.size = float(p.size);
    q.rotationDeg = float(p.rotationDeg);
    q.frame = uint32_t(p.frame);
    q.variant = hashKey(seed, p.id.stream ^ (uint32_t(p.id.index >> 32) * 0x9e3779b9U), uint32_t(p.id.index),
                        uint32_t(Attr::Variant));
    q.pad[0] = q.pad[1] = 0;
  }
  return out;
}

}  // namespace hs::particles
