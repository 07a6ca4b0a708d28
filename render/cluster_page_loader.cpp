#include "render/cluster_page_loader.h"

namespace hs::render {

DecodedPage layOutPage(const std::vector<mesh::PageCluster>& clusters) {
  DecodedPage d;
  for (const mesh::PageCluster& c : clusters) {
    const uint32_t base = uint32_t(d.positions.size());
    d.positions.insert(d.positions.end(), c.positions.begin(), c.positions.end());
    d.normals.insert(d.normals.end(), c.normals.begin(), c.normals.end());
    if (c.uvs.empty()) d.uvs.resize(d.positions.size(), glm::vec2(0.0f));
    else d.uvs.insert(d.uvs.end(), c.uvs.begin(), c.uvs.end());
    d.clusterFirstIndex.push_back(uint32_t(d.indices.size()));
    for (uint8_t t : c.triangles) d.indices.push_back(base + t);
  }
  return d;
}

ClusterPageLoader::ClusterPageLoader() : worker_([this] { run(); }) {}

ClusterPageLoader::~ClusterPageLoader() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
    queue_.clear();
  }
  wake_.notify_all();
  worker_.join();
}

void ClusterPageLoader::setBudget(size_t bytes) {
  std::lock_guard lock(mutex_);
  budget_ = bytes;
  trim();
}

void ClusterPageLoader::want(std::vector<PageRequest> pages) {
  {
    std::lock_guard lock(mutex_);
    queue_.clear();
    for (PageRequest& r : pages) {
      const PageKey key{r.asset.get(), r.page};
      if (!cache_.count(key) && !failed_.count(key)) queue_.push_back(std::move(r));
    }
  }
  wake_.notify_all();
}

std::shared_ptr<const DecodedPage> ClusterPageLoader::get(const PageKey& key) {
  std::lock_guard lock(mutex_);
  auto it = cache_.find(key);
  if (it == cache_.end()) return nullptr;
  lru_.splice(lru_.begin(), lru_, it->second.lru);
  return it->second.page;
}

bool ClusterPageLoader::failed(const PageKey& key) const {
  std::lock_guard lock(mutex_);
  return failed_.count(key) > 0;
}

std::vector<std::string> ClusterPageLoader::takeProblems() {
  std::lock_guard lock(mutex_);
  return std::exchange(problems_, {});
}

void ClusterPageLoader::waitIdle() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [&] { return queue_.empty() && !working_; });
}

void ClusterPageLoader::forget(const scene::ClusterAsset* asset) {
  std::lock_guard lock(mutex_);
  for (auto it = cache_.begin(); it != cache_.end();) {
    if (it->first.asset == asset) {
      bytes_ -= it->second.page->bytes();
      lru_.erase(it->second.lru);
      it = cache_.erase(it);
    } else {
      ++it;
    }
  }
  for (auto it = failed_.begin(); it != failed_.end();) it = it->first.asset == asset ? failed_.erase(it) : ++it;
}

size_t ClusterPageLoader::cachedBytes() const {
  std::lock_guard lock(mutex_);
  return bytes_;
}

size_t ClusterPageLoader::cachedPages() const {
  std::lock_guard lock(mutex_);
  return cache_.size();
}

size_t ClusterPageLoader::pending() const {
  std::lock_guard lock(mutex_);
  return queue_.size() + (working_ ? 1 : 0);
}

// The least recently used pages give way; the newest always stays (a
// budget under one page still draws).
void ClusterPageLoader::trim() {
  while (bytes_ > budget_ && lru_.size() > 1) {
    const PageKey victim = lru_.back();
    lru_.pop_back();
    auto it = cache_.find(victim);
    bytes_ -= it->second.page->bytes();
    cache_.erase(it);
  }
}

void ClusterPageLoader::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    if (queue_.empty()) idle_.notify_all();
    wake_.wait(lock, [&] { return stop_ || !queue_.empty(); });
    if (stop_) return;
    PageRequest r = std::move(queue_.front());
    queue_.pop_front();
    const PageKey key{r.asset.get(), r.page};
    if (cache_.count(key) || failed_.count(key)) continue;
    working_ = true;
    lock.unlock();
    // Read and decode without the lock: the render thread keeps asking.
    std::string error;
    auto clusters = r.asset->loadPage(r.page, r.what, error);
    std::shared_ptr<const DecodedPage> page;
    if (clusters) page = std::make_shared<const DecodedPage>(layOutPage(*clusters));
    lock.lock();
    working_ = false;
    if (page) {
      lru_.push_front(key);
      cache_[key] = {page, lru_.begin()};
      bytes_ += page->bytes();
      trim();
    } else {
      failed_[key] = error;
      problems_.push_back(error);
    }
  }
}

}  // namespace hs::render
