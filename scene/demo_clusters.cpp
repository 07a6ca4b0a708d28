#include "scene/demo_clusters.h"

#include "scene/cluster_asset.h"
#include "scene/import_pipeline.h"
#include "scene/mesh_materials.h"
#include "sequencer/camera_path.h"

namespace hs::scene {

void addDemoClusterScan(SceneState& s, const mesh::MeshData& bunny) {
  // As `import --clusters on` builds it, with a coarser stand-in (8k
  // triangles) so the cut's detail shows against it.
  ClusterBuild built = buildClusterAsset(bunny, {}, kClusterProxyTriangles / 8);
  mesh::MeshData proxy = std::move(built.proxy);
  proxy.materials = bunny.materials;
  if (!proxy.materials.empty()) proxy.submeshes.front().material = 0;
  MeshAsset a;
  a.id = s.maxAssetId() + 1;
  a.name = "Stanford Bunny (cluster hierarchy)";
  a.sourcePath = "resources/demo/stanford-bunny.obj";
  a.contentHash = mesh::contentHash(proxy);
  a.data = std::make_shared<const mesh::MeshData>(std::move(proxy));
  a.clustersHash = built.clustersHash;
  a.clusters = std::move(built.clusters);
  const mesh::Bounds b = bunny.bounds();
  s.assets.emplace(a.id, a);
  addMeshMaterials(s, a.id);

  const double scale = 60.0;
  const glm::dvec3 place(4000.0, 0.0, 0.0);
  const glm::dvec3 base(b.center().x, b.center().y, b.min.z);
  Entity scan;
  scan.id = s.maxEntityId() + 1;
  scan.name = "Bunny Scan (clusters)";
  scan.transform.translation = place - base * scale;
  scan.transform.scale = glm::dvec3(scale);
  scan.mesh = MeshInstance{a.id};
  s.roots.push_back(scan.id);
  s.entities.emplace(scan.id, scan);

  Entity cam;
  cam.id = s.maxEntityId() + 1;
  cam.name = "Scan Camera";
  const glm::dvec3 eye = place + glm::dvec3(-5.0, -12.0, 6.5), target = place + glm::dvec3(0.0, 0.0, 4.0);
  cam.transform.translation = eye;
  cam.transform.rotation = sequencer::lookRotation(target - eye);
  cam.camera = Camera{};
  cam.camera->verticalFovDeg = 50.0;
  s.roots.push_back(cam.id);
  s.entities.emplace(cam.id, cam);
}

}  // namespace hs::scene
