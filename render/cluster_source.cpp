#include "render/cluster_source.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

#include "render/frame_context.h"
#include "render/material_binding.h"
#include "render/material_table.h"
#include "scene/mesh_materials.h"

namespace hs::render {
namespace {

struct DrawCommand {  // glMultiDrawElementsIndirect's
  uint32_t count = 0, instanceCount = 1, firstIndex = 0;
  int32_t baseVertex = 0;
  uint32_t baseInstance = 0;
};

// Whether cluster pages can draw the asset's material: they carry
// positions, normals and UVs, and the source draws opaque solids only.
bool drawableMaterial(const scene::SceneState& state, const scene::MeshAsset& a) {
  if (!a.data || a.data->submeshes.empty()) return false;
  const size_t slot = scene::materialSlotOf(*a.data, a.data->submeshes.front());
  const scene::Material* m =
      state.findMaterial(slot < a.materialSlots.size() ? a.materialSlots[slot] : scene::kNoMaterial);
  return !m || (m->normalMap == scene::kNoTexture && m->heightMap == scene::kNoTexture && m->opacity >= 1.0f &&
                !m->alphaCutout);
}

double maxScaleOf(const glm::dmat4& w) {
  return std::max({glm::length(glm::dvec3(w[0])), glm::length(glm::dvec3(w[1])), glm::length(glm::dvec3(w[2]))});
}
double minScaleOf(const glm::dmat4& w) {
  return std::min({glm::length(glm::dvec3(w[0])), glm::length(glm::dvec3(w[1])), glm::length(glm::dvec3(w[2]))});
}

}  // namespace

class ClusterSource final : public DrawSource {
 public:
  struct Instance {
    uint32_t draw = 0;
    ClusterSources::AssetState* state = nullptr;
    glm::dmat4 world{1.0};
    double maxScale = 1.0;
    std::vector<uint32_t> clusters;  // the cut, resident
    std::vector<int32_t> slots;      // each cluster's page's slot
  };
  // A run of commands of one instance and level in one view.
  struct Range {
    uint32_t instance = 0, level = 0, first = 0, count = 0;
  };

  ClusterSource(ClusterSources& owner, VisibleSet& visible) : owner_(owner), visible_(visible) {}

  bool has(DrawVariant variant, SurfaceSet surfaces) const override {
    if (instances_.empty()) return false;
    switch (variant) {
      case DrawVariant::Surface: return surfaces != SurfaceSet::Translucent;  // opaque materials only (drawableMaterial)
      case DrawVariant::Pick: return true;
      case DrawVariant::Depth:
        for (size_t v = cameraViews_; v < ranges_.size(); ++v)
          if (!ranges_[v].empty()) return true;
        return false;
    }
    return false;
  }

  void cullShadowViews(FrameContext& frame, size_t first, size_t count) override {
    // Shadow view v is ranges_[cameraViews_ + v]: the same cut, culled by its volume.
    ranges_.resize(cameraViews_ + first + count);
    for (size_t v = first; v < first + count; ++v) {
      const Frustum& volume = frame.shadowViews[v];
      addCommands(cameraViews_ + v, [&](const glm::dvec3& centre, double r) {
        return volume.intersectsSphere(centre - visible_.origin, r);
      });
    }
  }

  void draw(FrameContext& frame, const DrawCall& call, const PassResources&) override {
    const size_t v = call.variant == DrawVariant::Depth ? cameraViews_ + call.shadowView : call.view;
    if (v >= ranges_.size() || ranges_[v].empty()) return;
    prepare(frame);
    glBindVertexArray(owner_.pool_.vao());
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, owner_.commands_.buffer.id());
    auto multiDraw = [&](const Range& r) {
      glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                                  reinterpret_cast<const void*>(uintptr_t(r.first) * sizeof(DrawCommand)),
                                  GLsizei(r.count), 0);
      ++frame.stats.drawCalls;
    };
    switch (call.variant) {
      case DrawVariant::Depth:
        frame.res.program({"mesh.vert", "shadow_depth.frag", "", {}}).use();
        for (const Range& r : ranges_[v]) multiDraw(r);
        break;
      case DrawVariant::Pick: {
        GlProgram& p = frame.res.program({"mesh.vert", "pick.frag", "", {}});
        p.use();
        p.set("uPickBase", call.pickBase);
        for (const Range& r : ranges_[v]) multiDraw(r);
        break;
      }
      case DrawVariant::Surface: {
        const bool lit = call.surfaces == SurfaceSet::Opaque;
        if (lit && frame.options.clusterLevels && call.fragment.empty()) {
          GlProgram& p = frame.res.program({"mesh.vert", "cluster_level.frag", "", call.defines});
          p.use();
          for (const Range& r : ranges_[v]) {
            p.set("uLevel", r.level);
            multiDraw(r);
          }
        } else {
          MaterialBinding binding(frame, call.defines, call.fragment);
          uint32_t bound = UINT32_MAX;
          for (const Range& r : ranges_[v]) {
            if (r.instance != bound) {
              DrawMaterial mat = frame.res.materials.forDraw(instances_[r.instance].draw, 0);
              mat.uvBounds = glm::vec4(0.0f);  // the coarse mesh's UV range is not the scan's
              binding.apply(mat);
              bound = r.instance;
            }
            multiDraw(r);
          }
          binding.finish();
        }
        if (lit) {
          for (size_t i = 0; i < instances_.size(); ++i) frame.stats.trianglesDrawn += triangles_[v][i];
          frame.stats.instancesDrawn += instances_.size();
        }
        break;
      }
    }
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  }

  size_t triangles(SurfaceSet surfaces) const override {
    if (surfaces == SurfaceSet::Translucent) return 0;
    size_t n = 0;
    for (const Instance& in : instances_)
      for (uint32_t c : in.clusters) n += in.state->asset->index.clusters[c].triangleCount;
    return n;
  }
  uint32_t pickIds() const override { return uint32_t(visible_.draws.size()); }
  PickedItem picked(uint32_t k) const override {
    return k < visible_.entities.size() ? PickedItem{visible_.entities[k], UINT32_MAX} : PickedItem{};
  }

  // The camera views' commands, culled by each view's frustum.
  void addCameraCommands(const std::vector<RenderView>& views) {
    cameraViews_ = views.size();
    ranges_.assign(cameraViews_, {});
    for (size_t v = 0; v < views.size(); ++v) {
      const Frustum f = frustumOf(views[v]);
      addCommands(v, [&](const glm::dvec3& centre, double r) { return f.intersectsSphere(centre - views[v].eye, r); });
    }
  }

  std::vector<Instance> instances_;

 private:
  // Commands of view `v` for every instance's clusters that `inside` keeps,
  // grouped by instance and level (the level view colours a range at a time).
  template <class Inside>
  void addCommands(size_t v, const Inside& inside) {
    triangles_.resize(ranges_.size());
    triangles_[v].assign(instances_.size(), 0);
    const ClusterGpuPool& pool = owner_.pool_;
    for (uint32_t i = 0; i < instances_.size(); ++i) {
      const Instance& in = instances_[i];
      const mesh::ClusterIndex& index = in.state->asset->index;
      const uint32_t object = visible_.draws[in.draw].object;
      std::vector<std::pair<uint32_t, DrawCommand>> kept;
      for (size_t k = 0; k < in.clusters.size(); ++k) {
        const mesh::ClusterIndexEntry& e = index.clusters[in.clusters[k]];
        const glm::dvec3 centre = glm::dvec3(in.world * glm::dvec4(glm::dvec3(e.bounds.centre), 1.0));
        if (!inside(centre, double(e.bounds.radius) * in.maxScale)) continue;
        const int32_t slot = in.slots[k];
        DrawCommand c;
        c.count = e.triangleCount * 3;
        c.firstIndex = uint32_t(size_t(slot) * pool.slotIndices() +
                                pool.clusterFirst(slot)[in.clusters[k] - index.pageFirst[e.page]]);
        c.baseVertex = int32_t(size_t(slot) * pool.slotVertices());
        c.baseInstance = object;
        kept.emplace_back(e.level, c);
        triangles_[v][i] += e.triangleCount;
      }
      std::stable_sort(kept.begin(), kept.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      for (size_t k = 0; k < kept.size();) {
        Range r{i, kept[k].first, uint32_t(commands_.size()), 0};
        for (; k < kept.size() && kept[k].first == r.level; ++k, ++r.count) commands_.push_back(kept[k].second);
        ranges_[v].push_back(r);
      }
    }
    uploaded_ = false;
  }

  // Before the first draw: the commands uploaded, the pool's object stream set.
  void prepare(FrameContext& frame) {
    if (uploaded_) return;
    GrowingBuffer& b = owner_.commands_;
    b.reserve(std::max<size_t>(commands_.size(), 1) * sizeof(DrawCommand));
    b.upload(commands_.data(), commands_.size() * sizeof(DrawCommand));
    owner_.pool_.setObjectIndexBuffer(frame.res.objectIndices.buffer.id());
    uploaded_ = true;
  }

  ClusterSources& owner_;
  VisibleSet& visible_;
  size_t cameraViews_ = 0;
  std::vector<std::vector<Range>> ranges_;       // per view: camera views, then shadow views
  std::vector<std::vector<size_t>> triangles_;   // per view, per instance
  std::vector<DrawCommand> commands_;
  bool uploaded_ = false;
};

ClusterSources::ClusterSources() = default;
ClusterSources::~ClusterSources() = default;

void ClusterSources::clear() {
  source_.reset();
  pool_.clear();
  commands_.buffer.reset();
  commands_.capacity = 0;
}

std::vector<std::string> ClusterSources::takeProblems() { return loader_.takeProblems(); }

DrawSource* ClusterSources::update(FrameContext& frame, VisibleSet& visible, const std::vector<RenderView>& views) {
  const auto start = std::chrono::steady_clock::now();
  ++frame_;
  source_.reset();
  ClusterStats& stats = frame.stats.clusters;
  stats = {};
  const scene::SceneState* state = frame.world.state;
  auto source = std::make_unique<ClusterSource>(*this, visible);
  for (size_t i = 0; state && i < frame.world.meshes.size(); ++i) {
    const InstanceBounds& b = visible.instances[i];
    const scene::MeshAsset* asset = frame.world.meshes[i].asset;
    if (b.draw < 0 || size_t(b.draw) >= visible.inView || !asset->clusters || !drawableMaterial(*state, *asset))
      continue;
    AssetState& as = assets_[asset->clusters.get()];
    if (!as.asset) {
      as.asset = asset->clusters;
      as.what = "mesh asset " + std::to_string(asset->id) + " ('" + asset->name + "')";
      as.groups = mesh::clusterGroupsOf(as.asset->index);
      as.largestPage = mesh::largestPage(as.asset->index);
    }
    as.lastFrame = frame_;
    ClusterSource::Instance in;
    in.draw = uint32_t(b.draw);
    in.state = &as;
    in.world = frame.world.meshes[i].world;
    in.maxScale = maxScaleOf(in.world);
    source->instances_.push_back(std::move(in));
  }
  // Assets that left the scene (or changed) give their pages back.
  for (auto it = assets_.begin(); it != assets_.end();) {
    if (it->second.lastFrame + 120 < frame_) {
      pool_.forget(it->first);
      loader_.forget(it->first);
      it = assets_.erase(it);
    } else {
      ++it;
    }
  }
  if (source->instances_.empty()) return nullptr;

  // One slot size for every asset's pages; no more slots than their pages.
  size_t slotVertices = 0, slotIndices = 0, pages = 0;
  for (const auto& [key, as] : assets_) {
    slotVertices = std::max(slotVertices, as.largestPage.vertices);
    slotIndices = std::max(slotIndices, as.largestPage.indices);
    pages += as.asset->index.pageCount;
  }
  pool_.configure(slotVertices, slotIndices, size_t(frame.settings.clusterGpuBudgetMb * 1048576.0), pages);
  loader_.setBudget(size_t(frame.settings.clusterCpuBudgetMb * 1048576.0));

  const RenderView& lv = frame.lodView;
  const double focal = double(lv.height) / (2.0 * std::tan(0.5 * lv.fovY));
  // Refinement looks through the LOD view widened by a margin, not through
  // each drawn view: both eyes of a pair (drawn by one call or two) and
  // every shadow view then get the one cut, the eyes' frusta lying within.
  RenderView wide = lv;
  wide.fovY = std::min(lv.fovY * 1.25, glm::radians(170.0));
  wide.width = int(std::ceil(double(lv.width) * std::tan(0.5 * wide.fovY) / std::tan(0.5 * lv.fovY)));
  const Frustum lodFrustum = frustumOf(wide);
  std::vector<mesh::ResidentCut> cuts(source->instances_.size());
  std::vector<PageRequest> requests;
  // Cut, upload what the cache has, cut again while that changed anything;
  // a frame that may not stream also waits for the pages it lacks.
  for (int round = 0; round < 256; ++round) {
    // Each round protects only what its own cut draws: the pages an earlier
    // round drew and this one refined past may give way to finer ones.
    ++stamp_;
    requests.clear();
    for (size_t k = 0; k < source->instances_.size(); ++k) {
      ClusterSource::Instance& in = source->instances_[k];
      const scene::ClusterAsset& a = *in.state->asset;
      const glm::dmat4 inverse = glm::inverse(in.world);
      // An error e seen at distance d on an instance scaled by s covers as
      // many pixels as e at d / s: the cut runs in the asset's own metres,
      // with the focal length stretched by the scale's spread.
      const double spread = in.maxScale / std::max(minScaleOf(in.world), 1e-12);
      mesh::CutViewer viewer{glm::vec3(inverse * glm::dvec4(lv.eye, 1.0)), float(focal * spread),
                             float(frame.settings.meshLodErrorPixels)};
      auto visibleSphere = [&](const mesh::LodSphere& s) {
        const glm::dvec3 centre = glm::dvec3(in.world * glm::dvec4(glm::dvec3(s.centre), 1.0));
        return lodFrustum.intersectsSphere(centre - lv.eye, double(s.radius) * in.maxScale);
      };
      const scene::ClusterAsset* key = &a;
      cuts[k] = mesh::selectResidentCut(a.index, in.state->groups, viewer,
                                        [&](uint32_t p) { return pool_.resident({key, p}); }, visibleSphere);
      // The roots never give way (without them the scan has nothing to draw).
      for (uint32_t p : in.state->groups.rootPages) pool_.use({key, p}, UINT64_MAX);
      // What this frame draws stays while the others' pages arrive.
      for (uint32_t c : cuts[k].clusters) pool_.use({key, a.index.clusters[c].page}, stamp_);
      for (uint32_t p : cuts[k].wanted)
        if (!loader_.failed({key, p})) requests.push_back({in.state->asset, p, in.state->what});
    }
    bool uploaded = false, full = false;
    for (const PageRequest& r : requests) {
      const PageKey key{r.asset.get(), r.page};
      if (auto page = loader_.get(key)) {
        if (pool_.upload(key, *page, stamp_)) uploaded = true;
        else full = true;
      }
    }
    stats.budgetFull = full;
    if (uploaded) continue;
    if (frame.options.streamClusters || requests.empty() || full) break;
    // Not streaming: wait for the pages, unless none of them can come.
    const size_t before = loader_.cachedPages();
    loader_.want(requests);
    loader_.waitIdle();
    if (loader_.cachedPages() == before && std::none_of(requests.begin(), requests.end(), [&](const PageRequest& r) {
          return loader_.get({r.asset.get(), r.page}) != nullptr;
        }))
      break;
  }
  loader_.want(requests);
  stats.pagesLoading = requests.size();

  // The instances whose roots are resident draw their cut; the others
  // their coarse mesh (the mesh source) until the roots arrive.
  std::vector<ClusterSource::Instance> drawn;
  for (size_t k = 0; k < source->instances_.size(); ++k) {
    ClusterSource::Instance& in = source->instances_[k];
    stats.complete = stats.complete && cuts[k].complete;
    stats.pagesWanted += cuts[k].wanted.size();
    if (!cuts[k].rootsResident) continue;
    const scene::ClusterAsset* key = in.state->asset.get();
    in.clusters = std::move(cuts[k].clusters);
    std::set<uint32_t> pagesDrawn;
    for (uint32_t c : in.clusters) {
      in.slots.push_back(pool_.use({key, key->index.clusters[c].page}, stamp_));
      pagesDrawn.insert(key->index.clusters[c].page);
    }
    stats.pagesDrawn += pagesDrawn.size();
    visible.byOtherSource[in.draw] = 1;
    ++stats.instances;
    stats.clusters += in.clusters.size();
    for (uint32_t c : in.clusters) stats.triangles += key->index.clusters[c].triangleCount;
    drawn.push_back(std::move(in));
  }
  source->instances_ = std::move(drawn);
  stats.pagesResident = pool_.residentPages();
  stats.gpuBytes = pool_.bytes();
  stats.cpuBytes = loader_.cachedBytes();
  stats.cutMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (source->instances_.empty()) return nullptr;
  source->addCameraCommands(views);
  source_ = std::move(source);
  return source_.get();
}

}  // namespace hs::render
