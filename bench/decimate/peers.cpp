#include "peers.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "mesh/mesh_import.h"
#include "mesh/weld.h"

namespace hs::bench {
namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

bool onPath(const char* tool) {
  const char* path = std::getenv("PATH");
  std::string p = path ? path : "/usr/bin:/bin";
  for (size_t b = 0; b <= p.size();) {
    size_t e = p.find(':', b);
    if (e == std::string::npos) e = p.size();
    if (e > b && fs::exists(fs::path(p.substr(b, e - b)) / tool)) return true;
    b = e + 1;
  }
  return false;
}

// Runs a shell command, returns its exit status and its output.
int run(const std::string& command, std::string& output) {
  output.clear();
  FILE* f = ::popen((command + " 2>&1").c_str(), "r");
  if (!f) return -1;
  char buf[4096];
  while (size_t n = std::fread(buf, 1, sizeof buf, f)) output.append(buf, n);
  return ::pclose(f);
}

// Positions welded (one per point), UVs per corner.
struct Welded {
  std::vector<uint32_t> posOf;
  std::vector<uint32_t> first;  // a vertex of each welded point
};
Welded weld(const hs::mesh::MeshData& in) {
  Welded w;
  uint32_t n = 0;
  w.posOf = hs::mesh::weldMap(in.positions, {}, {}, n);
  w.first.assign(n, UINT32_MAX);
  for (size_t v = in.positions.size(); v-- > 0;) w.first[w.posOf[v]] = uint32_t(v);
  return w;
}

void writeObj(const hs::mesh::MeshData& in, const std::string& path) {
  const Welded w = weld(in);
  std::ofstream f(path);
  char line[160];
  for (uint32_t v : w.first) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", double(in.positions[v].x), double(in.positions[v].y),
                  double(in.positions[v].z));
    f << line;
  }
  const bool uv = in.uvs.size() == in.positions.size();
  if (uv)
    for (const auto& t : in.uvs) {
      std::snprintf(line, sizeof line, "vt %.9g %.9g\n", double(t.x), double(t.y));
      f << line;
    }
  for (size_t c = 0; c < in.indices.size(); c += 3) {
    f << "f";
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t v = in.indices[c + k];
      f << ' ' << w.posOf[v] + 1;
      if (uv) f << '/' << v + 1;
    }
    f << '\n';
  }
}

void writePly(const hs::mesh::MeshData& in, const std::string& path) {
  const Welded w = weld(in);
  std::ofstream f(path, std::ios::binary);
  f << "ply\nformat binary_little_endian 1.0\nelement vertex " << w.first.size()
    << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << in.triangleCount()
    << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (uint32_t v : w.first) f.write(reinterpret_cast<const char*>(&in.positions[v].x), 12);
  for (size_t c = 0; c < in.indices.size(); c += 3) {
    const uint8_t three = 3;
    const int32_t t[3] = {int32_t(w.posOf[in.indices[c]]), int32_t(w.posOf[in.indices[c + 1]]),
                          int32_t(w.posOf[in.indices[c + 2]])};
    f.write(reinterpret_cast<const char*>(&three), 1);
    f.write(reinterpret_cast<const char*>(t), sizeof t);
  }
}

// The result in the input's frame: the file holds the input's local
// coordinates (Z up, as written).
bool readBack(const std::string& path, const hs::mesh::MeshData& in, PeerRun& r) {
  hs::mesh::ImportOptions io;
  io.up = hs::mesh::UpAxis::Z;
  hs::mesh::ImportResult back = hs::mesh::importMesh(path, io);
  if (!back.ok()) {
    r.note = "could not read its result: " + back.error;
    return false;
  }
  r.mesh = std::move(*back.mesh);
  r.mesh.origin += in.origin;
  r.ran = true;
  return true;
}

}  // namespace

PeerRun runBlenderDecimate(const hs::mesh::MeshData& in, double ratio, const std::string& workDir) {
  PeerRun r;
  if (!onPath("blender")) {
    r.note = "skipped: blender is not installed (Debian: apt-get install blender)";
    return r;
  }
  const std::string src = workDir + "/hs_peer_in.obj", dst = workDir + "/hs_peer_blender.obj",
                    script = workDir + "/hs_peer_blender.py";
  writeObj(in, src);
  std::ofstream(script) << R"(import bpy, sys, time
argv = sys.argv[sys.argv.index("--") + 1:]
src, dst, ratio = argv[0], argv[1], float(argv[2])
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.wm.obj_import(filepath=src, forward_axis='Y', up_axis='Z')
obj = bpy.context.selected_objects[0]
bpy.context.view_layer.objects.active = obj
mod = obj.modifiers.new("hs_decimate", 'DECIMATE')
mod.decimate_type = 'COLLAPSE'
mod.ratio = ratio
t = time.perf_counter()
bpy.ops.object.modifier_apply(modifier=mod.name)
t = time.perf_counter() - t
bpy.ops.wm.obj_export(filepath=dst, forward_axis='Y', up_axis='Z', export_selected_objects=True, export_uv=True,
                      export_normals=False, export_materials=False, export_triangulated_mesh=True)
print("HS_DECIMATE_SECONDS %.6f" % t)
)";
  char ratioText[32];
  std::snprintf(ratioText, sizeof ratioText, "%.9g", ratio);
  std::string out;
  const int status = run("blender -b --factory-startup -P '" + script + "' -- '" + src + "' '" + dst + "' " + ratioText, out);
  const size_t at = out.find("HS_DECIMATE_SECONDS ");
  if (status != 0 || at == std::string::npos) {
    r.note = "blender failed (status " + std::to_string(status) + "): " + out.substr(out.size() > 400 ? out.size() - 400 : 0);
    return r;
  }
  r.seconds = std::atof(out.c_str() + at + 20);
  r.note = "modifier apply only (1 thread)";
  readBack(dst, in, r);
  return r;
}

PeerRun runMeshlabDecimate(const hs::mesh::MeshData& in, size_t targetTriangles, const std::string& workDir) {
  PeerRun r;
  if (!onPath("meshlabserver") || !onPath("xvfb-run")) {
    r.note = "skipped: meshlabserver or xvfb-run is not installed (Debian: apt-get install meshlab xvfb)";
    return r;
  }
  const std::string src = workDir + "/hs_peer_in.ply", dst = workDir + "/hs_peer_meshlab.ply",
                    copy = workDir + "/hs_peer_meshlab_copy.ply", script = workDir + "/hs_peer_meshlab.mlx",
                    empty = workDir + "/hs_peer_meshlab_none.mlx";
  writePly(in, src);
  // MeshLab's defaults for the filter; 2020.09 aborts unless all 13 are given.
  std::ofstream(script) << "<!DOCTYPE FilterScript>\n<FilterScript>\n"
                           " <filter name=\"Simplification: Quadric Edge Collapse Decimation\">\n"
                           "  <Param type=\"RichInt\" value=\"" << targetTriangles << "\" name=\"TargetFaceNum\"/>\n"
                           R"(  <Param type="RichFloat" value="0" name="TargetPerc"/>
  <Param type="RichFloat" value="0.3" name="QualityThr"/>
  <Param type="RichBool" value="false" name="PreserveBoundary"/>
  <Param type="RichFloat" value="1" name="BoundaryWeight"/>
  <Param type="RichBool" value="false" name="PreserveNormal"/>
  <Param type="RichBool" value="false" name="PreserveTopology"/>
  <Param type="RichBool" value="true" name="OptimalPlacement"/>
  <Param type="RichBool" value="false" name="PlanarQuadric"/>
  <Param type="RichFloat" value="0.001" name="PlanarWeight"/>
  <Param type="RichBool" value="false" name="QualityWeight"/>
  <Param type="RichBool" value="true" name="AutoClean"/>
  <Param type="RichBool" value="false" name="Selected"/>
 </filter>
</FilterScript>
)";
  std::ofstream(empty) << "<!DOCTYPE FilterScript>\n<FilterScript>\n</FilterScript>\n";
  auto timed = [&](const std::string& mlx, const std::string& output, std::string& log) {
    const auto t0 = Clock::now();
    const int status = run("xvfb-run -a meshlabserver -i '" + src + "' -o '" + output + "' -s '" + mlx + "'", log);
    return status == 0 ? std::chrono::duration<double>(Clock::now() - t0).count() : -1.0;
  };
  std::string log;
  const double without = timed(empty, copy, log);
  const double with = timed(script, dst, log);
  if (with < 0 || without < 0 || !fs::exists(dst)) {
    r.note = "meshlabserver failed: " + log.substr(log.size() > 400 ? log.size() - 400 : 0);
    return r;
  }
  r.seconds = std::max(0.0, with - without);
  char note[128];
  std::snprintf(note, sizeof note, "process wall %.2f s minus %.2f s without the filter (1 thread)", with, without);
  r.note = note;
  readBack(dst, in, r);
  return r;
}

}  // namespace hs::bench
