#include "foliage/store.h"

#include <algorithm>
#include <cstring>
#include <memory>

#include "core/content_hash.h"
#include "core/parallel.h"
#include "foliage/byte_io.h"
#include "foliage/zlib_bytes.h"

namespace hs::foliage {

// --- cells -------------------------------------------------------------------

size_t Cell::count() const {
  size_t n = 0;
  for (const Run& r : runs) n += r.items.size();
  return n;
}

Run& Cell::run(uint16_t type, Surface surface) {
  for (Run& r : runs)
    if (r.type == type && r.surface == surface) return r;
  runs.push_back(Run{type, surface, {}});
  return runs.back();
}

std::string cellName(const CellKey& k) {
  return "(" + std::to_string(k.x) + ", " + std::to_string(k.y) + ", " + std::to_string(k.z) + ")";
}
std::string cellBlobKey(const CellKey& k) {
  return "foliage/cell/" + std::to_string(k.x) + "_" + std::to_string(k.y) + "_" + std::to_string(k.z);
}

// --- blobs -------------------------------------------------------------------

namespace {

using byte_io::get;
using byte_io::put;

std::vector<uint8_t> rawPayload(const Cell& cell) {
  std::vector<uint8_t> raw;
  raw.reserve(cell.runs.size() * 8 + cell.count() * 16);
  for (const Run& r : cell.runs) {
    put<uint16_t>(raw, r.type);
    put<uint8_t>(raw, uint8_t(r.surface));
    put<uint8_t>(raw, 0);
    put<uint32_t>(raw, uint32_t(r.items.size()));
  }
  for (const Run& r : cell.runs) {
    const size_t n = r.items.size(), base = raw.size();
    raw.resize(base + n * 16);
    uint32_t prev = 0;
    for (size_t i = 0; i < n; ++i) {
      PackedInstance p = r.items[i];
      const uint32_t id = p.id;
      p.id = id - prev;
      prev = id;
      uint8_t b[16];
      std::memcpy(b, &p, 16);
      for (size_t k = 0; k < 16; ++k) raw[base + k * n + i] = b[k];
    }
  }
  return raw;
}

}  // namespace

uint64_t rawPayloadHash(const Cell& cell) {
  const std::vector<uint8_t> raw = rawPayload(cell);
  return contentHash(raw.data(), raw.size());
}

std::vector<uint8_t> encodeCell(const CellKey& key, const Cell& cell, int level) {
  const std::vector<uint8_t> raw = rawPayload(cell);
  std::vector<uint8_t> out;
  put<uint32_t>(out, 0x43465348u);  // "HSFC"
  put<uint16_t>(out, 1);
  put<uint16_t>(out, uint16_t(cell.runs.size()));
  put<int32_t>(out, key.x);
  put<int32_t>(out, key.y);
  put<int32_t>(out, key.z);
  put<uint32_t>(out, uint32_t(cell.count()));
  put<uint32_t>(out, uint32_t(raw.size()));
  const std::vector<uint8_t> payload = deflateBytes(raw.data(), raw.size(), level);
  put<uint32_t>(out, uint32_t(payload.size()));
  put<uint64_t>(out, contentHash(raw.data(), raw.size()));
  out.insert(out.end(), payload.begin(), payload.end());
  return out;
}

Status decodeCell(std::span<const uint8_t> blob, const CellKey& expected, size_t typeCount, Cell& out) {
  const std::string name = "foliage cell " + cellName(expected) + ": ";
  auto fail = [&](size_t offset, const std::string& what) {
    return Status{name + "byte offset " + std::to_string(offset) + ": " + what};
  };
  if (blob.size() < kCellHeaderBytes)
    return fail(blob.size(), "truncated: the blob has " + std::to_string(blob.size()) + " bytes, its header needs " +
                                 std::to_string(kCellHeaderBytes));
  const uint8_t* b = blob.data();
  if (get<uint32_t>(b) != 0x43465348u) return fail(0, "not a foliage cell blob (no \"HSFC\" signature)");
  if (get<uint16_t>(b + 4) != 1)
    return fail(4, "format version " + std::to_string(get<uint16_t>(b + 4)) + " is not one this build reads (1)");
  const size_t runs = get<uint16_t>(b + 6);
  const CellKey key{get<int32_t>(b + 8), get<int32_t>(b + 12), get<int32_t>(b + 16)};
  if (key != expected) return fail(8, "the blob is cell " + cellName(key) + "'s");
  const size_t count = get<uint32_t>(b + 20), rawBytes = get<uint32_t>(b + 24), payload = get<uint32_t>(b + 28);
  const uint64_t hash = get<uint64_t>(b + 32);
  if (rawBytes != runs * 8 + count * 16)
    return fail(24, "raw size " + std::to_string(rawBytes) + " does not match " + std::to_string(runs) + " runs and " +
                        std::to_string(count) + " instances");
  if (blob.size() < kCellHeaderBytes + payload)
    return fail(blob.size(), "truncated: the header declares " + std::to_string(payload) +
                                 " payload bytes from byte offset 40, the blob ends after " +
                                 std::to_string(blob.size() - kCellHeaderBytes));
  if (blob.size() > kCellHeaderBytes + payload)
    return fail(kCellHeaderBytes + payload, std::to_string(blob.size() - kCellHeaderBytes - payload) +
                                                " bytes after the payload's end");
  std::vector<uint8_t> raw(rawBytes);
  if (!inflateBytes(b + kCellHeaderBytes, payload, raw.data(), raw.size()))
    return fail(kCellHeaderBytes, "the compressed payload (bytes 40 to " + std::to_string(kCellHeaderBytes + payload) +
                                      ") is corrupt or of the wrong size");
  if (contentHash(raw.data(), raw.size()) != hash)
    return fail(32, "content hash mismatch (stored " + toHex(hash) + ", payload hashes to " +
                        toHex(contentHash(raw.data(), raw.size())) + ")");
  Cell cell;
  cell.runs.resize(runs);
  size_t total = 0;
  for (size_t i = 0; i < runs; ++i) {
    const uint8_t* p = raw.data() + i * 8;
    Run& run = cell.runs[i];
    run.type = get<uint16_t>(p);
    const uint8_t surface = p[2];
    const size_t n = get<uint32_t>(p + 4);
    const std::string where = "raw payload byte offset " + std::to_string(i * 8) + " (run " + std::to_string(i) + ")";
    if (run.type >= typeCount)
      return Status{name + where + ": type " + std::to_string(run.type) + " is not one of the scene's " +
                    std::to_string(typeCount) + " foliage types"};
    if (surface > 1) return Status{name + where + ": surface " + std::to_string(surface) + " is not 0 or 1"};
    if (n > count - total) return Status{name + where + ": its " + std::to_string(n) + " instances exceed the header's"};
    run.surface = Surface(surface);
    run.items.resize(n);
    total += n;
  }
  if (total != count)
    return Status{name + "the runs hold " + std::to_string(total) + " instances, the header " + std::to_string(count)};
  size_t base = runs * 8;
  for (Run& run : cell.runs) {
    const size_t n = run.items.size();
    uint32_t prev = 0;
    for (size_t i = 0; i < n; ++i) {
      uint8_t bytes[16];
      for (size_t k = 0; k < 16; ++k) bytes[k] = raw[base + k * n + i];
      PackedInstance p;
      std::memcpy(&p, bytes, 16);
      p.id += prev;
      prev = p.id;
      run.items[i] = p;
    }
    base += n * 16;
  }
  out = std::move(cell);
  return {};
}

// --- undo ----------------------------------------------------------------------

size_t FoliageUndo::bytes() const {
  size_t b = sizeof(*this);
  for (const Entry& e : cells_) {
    b += sizeof(Entry);
    if (e.cell)
      for (const Run& r : e.cell->runs) b += sizeof(Run) + r.items.capacity() * sizeof(PackedInstance);
  }
  return b;
}

std::vector<CellKey> FoliageUndo::keys() const {
  std::vector<CellKey> k;
  for (const Entry& e : cells_) k.push_back(e.key);
  return k;
}

void FoliageUndo::swap(FoliageStore& store) {
  for (Entry& e : cells_) {
    std::optional<Cell> current;
    if (auto it = store.cells_.find(e.key); it != store.cells_.end()) current = std::move(it->second);
    store.setCell(e.key, std::move(e.cell));
    e.cell = std::move(current);
  }
  if (hasNextId_) std::swap(nextId_, store.nextId_);
}

void FoliageUndo::merge(FoliageUndo&& later) {
  for (Entry& e : later.cells_)
    if (recorded_.insert(e.key).second) cells_.push_back(std::move(e));
  if (!hasNextId_ && later.hasNextId_) {
    nextId_ = later.nextId_;
    hasNextId_ = true;
  }
  later.cells_.clear();
  later.recorded_.clear();
}

size_t SaveSet::bytes() const {
  size_t b = 0;
  for (const auto& blob : blobs) b += blob.size();
  return b;
}

// --- the store -------------------------------------------------------------------

int FoliageStore::addType(const FoliageType& t, std::vector<std::string>& messages) {
  if (findType(t.name) >= 0) {
    messages.push_back("foliage type \"" + t.name + "\": name: a type of that name exists");
    return -1;
  }
  if (types_.size() >= 65535) {
    messages.push_back("foliage type \"" + t.name + "\": a scene holds at most 65535 foliage types");
    return -1;
  }
  types_.push_back(sanitized(t, messages));
  return int(types_.size() - 1);
}

int FoliageStore::findType(const std::string& name) const {
  for (size_t i = 0; i < types_.size(); ++i)
    if (types_[i].name == name) return int(i);
  return -1;
}

void FoliageStore::setType(size_t i, const FoliageType& t, FoliageUndo* undo, std::vector<std::string>& warnings) {
  const ScaleMode before = types_[i].scaleMode;
  types_[i] = sanitized(t, warnings);
  if (types_[i].scaleMode == before) return;
  std::vector<CellKey> keys;
  for (const auto& [k, c] : cells_)
    for (const Run& r : c.runs)
      if (r.type == i && !r.items.empty()) {
        keys.push_back(k);
        break;
      }
  for (const CellKey& k : keys)
    for (Run& r : edit(k, undo).runs)
      if (r.type == i)
        for (PackedInstance& p : r.items) p.scale = packScale(types_[i].scaleMode, unpackScale(before, p.scale));
}

size_t FoliageStore::instanceCount() const {
  size_t n = 0;
  for (const auto& [k, c] : cells_) n += c.count();
  return n;
}

size_t FoliageStore::instanceCount(uint16_t type) const {
  size_t n = 0;
  for (const auto& [k, c] : cells_)
    for (const Run& r : c.runs)
      if (r.type == type) n += r.items.size();
  return n;
}

const Cell* FoliageStore::cell(const CellKey& k) const {
  auto it = cells_.find(k);
  return it == cells_.end() ? nullptr : &it->second;
}

void FoliageStore::forEachCellIn(const glm::dvec2& lo, const glm::dvec2& hi,
                                 const std::function<void(const CellKey&, const Cell&)>& fn) const {
  if (!(lo.x <= hi.x && lo.y <= hi.y)) return;
  const int32_t x0 = cellOfSteps(toSteps(lo.x)), x1 = cellOfSteps(toSteps(hi.x));
  const int32_t y0 = cellOfSteps(toSteps(lo.y)), y1 = cellOfSteps(toSteps(hi.y));
  const uint64_t span = uint64_t(int64_t(x1) - x0 + 1) * uint64_t(int64_t(y1) - y0 + 1);
  if (span > columns_.size() * 4) {
    // A large rectangle: walk the columns that exist.
    std::vector<CellKey> keys;
    for (const auto& [ck, zs] : columns_) {
      const int32_t x = int32_t(ck >> 32), y = int32_t(uint32_t(ck));
      if (x < x0 || x > x1 || y < y0 || y > y1) continue;
      for (int32_t z : zs) keys.push_back({x, y, z});
    }
    std::sort(keys.begin(), keys.end());
    for (const CellKey& k : keys) fn(k, cells_.at(k));
    return;
  }
  for (int32_t y = y0; y <= y1; ++y)
    for (int32_t x = x0; x <= x1; ++x) {
      auto it = columns_.find(columnKey(x, y));
      if (it == columns_.end()) continue;
      for (int32_t z : it->second) {
        const CellKey k{x, y, z};
        fn(k, cells_.at(k));
      }
    }
}

std::vector<CellKey> FoliageStore::cellsIn(const glm::dvec2& lo, const glm::dvec2& hi) const {
  std::vector<CellKey> keys;
  forEachCellIn(lo, hi, [&](const CellKey& k, const Cell&) { keys.push_back(k); });
  return keys;
}

std::vector<Instance> FoliageStore::allInstances() const {
  std::vector<CellKey> keys;
  for (const auto& [k, c] : cells_) keys.push_back(k);
  std::sort(keys.begin(), keys.end());
  std::vector<Instance> out;
  for (const CellKey& k : keys)
    for (const Run& r : cells_.at(k).runs)
      for (const PackedInstance& p : r.items) {
        Instance in = unpack(p, types_[r.type].scaleMode, k);
        in.type = r.type;
        in.surface = r.surface;
        out.push_back(in);
      }
  return out;
}

std::optional<Instance> FoliageStore::find(uint32_t id) const {
  for (const auto& [k, c] : cells_)
    for (const Run& r : c.runs)
      for (const PackedInstance& p : r.items)
        if (p.id == id) {
          Instance in = unpack(p, types_[r.type].scaleMode, k);
          in.type = r.type;
          in.surface = r.surface;
          return in;
        }
  return std::nullopt;
}

void FoliageStore::touch(const CellKey& k) { revision_[k] = ++clock_; }

uint64_t FoliageStore::cellRevision(const CellKey& k) const {
  const auto it = revision_.find(k);
  return it == revision_.end() ? 0 : it->second;
}

void FoliageStore::setCell(const CellKey& k, std::optional<Cell> c) {
  const bool had = cells_.count(k) != 0;
  if (c) {
    cells_[k] = std::move(*c);
    if (!had) columns_[columnKey(k.x, k.y)].push_back(k.z);
  } else if (had) {
    cells_.erase(k);
    auto it = columns_.find(columnKey(k.x, k.y));
    auto& zs = it->second;
    zs.erase(std::find(zs.begin(), zs.end(), k.z));
    if (zs.empty()) columns_.erase(it);
  }
  touch(k);
}

Cell& FoliageStore::edit(const CellKey& k, FoliageUndo* undo) {
  auto it = cells_.find(k);
  if (undo && undo->recorded_.insert(k).second) {
    FoliageUndo::Entry e{k, std::nullopt};
    if (it != cells_.end()) e.cell = it->second;
    undo->cells_.push_back(std::move(e));
  }
  if (it == cells_.end()) {
    setCell(k, Cell{});
    it = cells_.find(k);
  } else {
    touch(k);
  }
  return it->second;
}

void FoliageStore::recordNextId(FoliageUndo* undo) const {
  if (undo && !undo->hasNextId_) {
    undo->nextId_ = nextId_;
    undo->hasNextId_ = true;
  }
}

uint32_t FoliageStore::takeIds(uint32_t n, FoliageUndo* undo) {
  recordNextId(undo);
  const uint32_t first = nextId_;
  nextId_ += n;
  return first;
}

uint32_t FoliageStore::add(Instance in, FoliageUndo* undo, bool keepId) {
  if (!keepId) {
    recordNextId(undo);
    in.id = nextId_++;
  }
  const CellKey k = cellOf(in.position);
  edit(k, undo).run(in.type, in.surface).items.push_back(pack(in, types_[in.type].scaleMode, k));
  return in.id;
}

void FoliageStore::prune(const std::vector<CellKey>& keys) {
  for (const CellKey& k : keys) {
    auto it = cells_.find(k);
    if (it == cells_.end()) continue;
    auto& runs = it->second.runs;
    runs.erase(std::remove_if(runs.begin(), runs.end(), [](const Run& r) { return r.items.empty(); }), runs.end());
    if (runs.empty()) setCell(k, std::nullopt);
  }
}

SaveSet FoliageStore::dirty(unsigned threads) const {
  SaveSet s;
  for (const auto& [k, c] : cells_) {
    auto saved = savedRevision_.find(k);
    auto rev = revision_.find(k);
    if (saved == savedRevision_.end() || rev == revision_.end() || saved->second != rev->second) s.write.push_back(k);
  }
  for (const auto& [k, r] : savedRevision_)
    if (!cells_.count(k)) s.remove.push_back(k);
  std::sort(s.write.begin(), s.write.end());
  std::sort(s.remove.begin(), s.remove.end());
  s.blobs.resize(s.write.size());
  parallelFor(int64_t(s.write.size()), int(threads), 1, [&](int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i) s.blobs[size_t(i)] = encodeCell(s.write[size_t(i)], cells_.at(s.write[size_t(i)]));
  });
  return s;
}

size_t FoliageStore::dirtyCount() const {
  size_t n = 0;
  for (const auto& [k, c] : cells_) {
    auto saved = savedRevision_.find(k);
    if (saved == savedRevision_.end() || saved->second != revision_.at(k)) ++n;
  }
  for (const auto& [k, r] : savedRevision_)
    if (!cells_.count(k)) ++n;
  return n;
}

void FoliageStore::markSaved() {
  savedRevision_.clear();
  for (const auto& [k, c] : cells_) savedRevision_[k] = revision_.at(k);
}

Status FoliageStore::load(const CellKey& key, std::span<const uint8_t> blob) {
  Cell c;
  Status s = decodeCell(blob, key, types_.size(), c);
  if (!s) return s;
  for (const Run& r : c.runs)
    for (const PackedInstance& p : r.items) nextId_ = std::max(nextId_, p.id + 1);
  setCell(key, std::move(c));
  savedRevision_[key] = revision_.at(key);
  return {};
}

}  // namespace hs::foliage
