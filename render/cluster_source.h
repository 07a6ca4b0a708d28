#pragma once
// Mesh assets with a cluster hierarchy (huge scans; scene/cluster_asset.h)
// as a draw source (draw_source.h; issue 38 items 3-4).
//
// Each frame, for every instance of such an asset in view, one cut through
// its hierarchy chosen from the frame's LOD view (meshproc/cluster_cut.h:
// each cluster's error projected under SceneSettings::meshLodErrorPixels,
// the bound mesh LODs take; both eyes of a pair and every shadow view draw
// that one cut), over the pages resident on the GPU (cluster_gpu_pool.h);
// groups outside the LOD view's frustum (widened by a margin, so both eyes
// and the views around it get the same cut) are not refined. Pages the cut wants and
// lacks are read by a worker (cluster_page_loader.h) into the CPU cache
// and uploaded when they arrive; until then the coarser level stays
// (never a hole). In the editor's viewport (RenderOptions::streamClusters)
// a frame draws what is resident and the next frames catch up; every other
// frame (exports, render nodes, tests) waits until its cut is whole, so
// exported frames are the same in any run and under any budget the cut fits.
// An instance whose roots are not resident yet, or whose material needs
// what cluster pages do not carry (tangents for normal or height maps,
// translucency, alpha cut-out), is drawn by the mesh source from its coarse
// mesh (MeshAsset::data) instead.
//
// The cut's clusters are drawn with glMultiDrawElementsIndirect, one
// command a cluster (its slot's vertices and its triangles), per camera
// view culled by its bounding sphere, and per shadow view by the shadow
// volume; materials, object matrices and pick ids are the visible set's
// (the instance's draw there). RenderOptions::clusterLevels colours each
// cluster by its level instead (shaders/cluster_level.frag).
// Include only inside render/.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "meshproc/cluster_cut.h"
#include "render/cluster_gpu_pool.h"
#include "render/cluster_page_loader.h"
#include "render/draw_source.h"
#include "render/render_resources.h"
#include "render/visible_set.h"

namespace hs::render {

class ClusterSource;

// Lives as long as the renderer: the page cache, the GPU pool and each
// asset's groups persist across frames.
class ClusterSources {
 public:
  ClusterSources();
  ~ClusterSources();
  // The frame's cluster source, or null when no clustered instance is in
  // view. Marks the draws it takes in visible.byOtherSource.
  DrawSource* update(FrameContext& frame, VisibleSet& visible, const std::vector<RenderView>& views);
  // Pages that failed to load since the last call (one message each).
  std::vector<std::string> takeProblems();
  void clear();  // the GL objects (the context is about to go)

 private:
  friend class ClusterSource;
  struct AssetState {
    std::shared_ptr<const scene::ClusterAsset> asset;
    std::string what;  // "mesh asset 3 ('Scan')", for messages
    mesh::ClusterGroups groups;
    mesh::PageExtent largestPage;  // what a slot needs for its pages
    uint64_t lastFrame = 0;
  };
  ClusterPageLoader loader_;
  ClusterGpuPool pool_;
  GrowingBuffer commands_;  // the frame's indirect commands
  std::map<const scene::ClusterAsset*, AssetState> assets_;
  std::unique_ptr<ClusterSource> source_;
  uint64_t frame_ = 0;
  uint64_t stamp_ = 0;  // one per cut chosen: what the pool keeps from eviction
};

}  // namespace hs::render
