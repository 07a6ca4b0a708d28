// The frame graph and the renderer's resource registry, on a headless EGL
// context: culling (a pass nothing reads does not run and its resources are
// never allocated), versions of read-modify-write resources, pooling of
// transient textures between passes, eyes and frames, freeing what a frame
// no longer uses, kept outputs, timed passes that report their own work, a
// frame's GPU time never longer than the frame;
// and, through the real renderer, that each
// optional pass and its buffers exist only in frames that need them. Every
// check reads the pool's registry or the graph's records (what really ran
// and was allocated), not counters the passes keep about themselves.
#include <QtTest>

#include <algorithm>
#include <chrono>
#include <set>

#include <epoxy/gl.h>

#include "render/frame_graph.h"
#include "render/offscreen_renderer.h"
#include "render/resource_pool.h"
#include "scene/demo_scene.h"
#include "scene/demo_terrain.h"

using namespace hs;
using namespace hs::render;

namespace {

const TextureDesc kSmall{64, 32, GL_RGBA16F};

bool ran(const FrameGraph& g, const std::string& name) {
  for (const PassRecord& r : g.records())
    if (r.name == name) return r.ran;
  return false;
}

size_t allocated(const ResourcePool& pool, const std::string& prefix) {
  size_t n = 0;
  for (const PoolAllocation& a : pool.registry()) n += a.name.rfind(prefix, 0) == 0;
  return n;
}

struct NoData {};

// A pass writing into a texture it creates; returns the reference.
TextureRef producer(FrameGraph& g, const std::string& name, const std::string& texture, std::vector<std::string>* log) {
  struct D {
    TextureRef t;
  };
  return g
      .addPass<D>(
          name, [&](PassBuilder& b, D& d) { d.t = b.create(texture, kSmall); },
          [log, name](const D&, const PassResources&) {
            if (log) log->push_back(name);
          })
      .t;
}

void consumer(FrameGraph& g, const std::string& name, TextureRef t, std::vector<std::string>* log,
              GLuint* seen = nullptr) {
  struct D {
    TextureRef t;
  };
  g.addPass<D>(
      name,
      [&](PassBuilder& b, D& d) {
        d.t = b.read(t);
        b.sideEffect();
      },
      [log, name, seen](const D& d, const PassResources& r) {
        if (log) log->push_back(name);
        if (seen) *seen = r.texture(d.t);
      });
}

std::vector<std::string> passNames(const FrameStats& s) {
  std::vector<std::string> n;
  for (const PassStats& p : s.passes) n.push_back(p.name);
  return n;
}

bool has(const std::vector<std::string>& v, const std::string& x) { return std::find(v.begin(), v.end(), x) != v.end(); }

size_t registryBytes(const std::vector<GpuAllocation>& reg, const std::string& prefix) {
  size_t b = 0;
  for (const auto& a : reg)
    if (a.name.rfind(prefix, 0) == 0) b += a.bytes;
  return b;
}
size_t registryCount(const std::vector<GpuAllocation>& reg, const std::string& prefix) {
  size_t n = 0;
  for (const auto& a : reg) n += a.name.rfind(prefix, 0) == 0;
  return n;
}


// A program drawing one triangle over the viewport whose fragments each run
// `uIterations` rounds of arithmetic: GPU work that lies wholly in one draw,
// with no clear before it (as the terrain pass draws into the opaque pass's
// targets).
GLuint busyProgram() {
  static const char* vs =
      "#version 450 core\n"
      "void main() { vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2); gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0); }\n";
  static const char* fs =
      "#version 450 core\n"
      "uniform int uIterations;\n"
      "out vec4 color;\n"
      "void main() {\n"
      "  vec2 v = gl_FragCoord.xy * 1e-3;\n"
      "  for (int i = 0; i < uIterations; ++i) v = vec2(sin(v.x + v.y), cos(v.x - 0.5 * v.y));\n"
      "  color = vec4(v, 0.0, 1.0);\n"
      "}\n";
  const GLuint p = glCreateProgram();
  for (auto [type, src] : {std::pair{GL_VERTEX_SHADER, vs}, std::pair{GL_FRAGMENT_SHADER, fs}}) {
    const GLuint sh = glCreateShader(type);
    glShaderSource(sh, 1, &src, nullptr);
    glCompileShader(sh);
    glAttachShader(p, sh);
    glDeleteShader(sh);
  }
  glLinkProgram(p);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  return ok ? p : 0;
}

double millisSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

class TestFrameGraph : public QObject {
  Q_OBJECT
  OffscreenRenderer r_;
  scene::SceneState demo_;

 private slots:
  void initTestCase() {
    // Debug output on (gl/gl_debug.h): the context becomes a debug context.
    qputenv("HS_GL_DEBUG", "1");
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
    std::optional<scene::SceneState> d = scene::buildDemoScene(error);
    QVERIFY2(d, error.c_str());
    demo_ = std::move(*d);
  }

  // ---- the graph ---------------------------------------------------------------

  void unusedPassesAreCulledAndTheirResourcesNeverMade() {
    r_.makeCurrent();
    ResourcePool pool;
    std::vector<std::string> log;
    {
      FrameGraph g(pool);
      const TextureRef a = producer(g, "a", "tex_a", &log);
      producer(g, "unread", "tex_unread", &log);  // nothing reads it
      consumer(g, "out", a, &log);
      g.execute();
      QCOMPARE(log, (std::vector<std::string>{"a", "out"}));
      QVERIFY(!ran(g, "unread"));
      QCOMPARE(allocated(pool, "tex_unread"), size_t(0));
      QCOMPARE(allocated(pool, "tex_a"), size_t(1));
    }
    // A pass with no side effect whose output nothing reads, alone: nothing runs.
    log.clear();
    FrameGraph g(pool);
    producer(g, "lonely", "tex_lonely", &log);
    g.execute();
    QVERIFY(log.empty());
    QCOMPARE(allocated(pool, "tex_lonely"), size_t(0));
  }

  // Writes make versions: a pass whose version is overwritten before anyone
  // reads it is dead, a read-modify-write keeps its producer alive.
  void versionsDecideWhoIsNeeded() {
    r_.makeCurrent();
    ResourcePool pool;
    std::vector<std::string> log;
    FrameGraph g(pool);
    struct D {
      TextureRef t;
    };
    const TextureRef t = producer(g, "first", "tex", &log);  // version 1
    g.addPass<D>(
        "blend", [&](PassBuilder& b, D& d) { d.t = b.write(b.read(t)); },  // reads 1, writes 2
        [&](const D&, const PassResources&) { log.push_back("blend"); });
    g.addPass<D>(
        "overwrite", [&](PassBuilder& b, D& d) { d.t = b.write(t); },  // writes 3 without reading 2
        [&](const D&, const PassResources&) { log.push_back("overwrite"); });
    consumer(g, "out", t, &log);  // reads 3
    g.execute();
    QCOMPARE(log, (std::vector<std::string>{"overwrite", "out"}));

    // Without the overwrite, the chain first -> blend -> out is needed.
    log.clear();
    FrameGraph h(pool);
    const TextureRef u = producer(h, "first", "tex", &log);
    h.addPass<D>(
        "blend", [&](PassBuilder& b, D& d) { d.t = b.write(b.read(u)); },
        [&](const D&, const PassResources&) { log.push_back("blend"); });
    consumer(h, "out", u, &log);
    h.execute();
    QCOMPARE(log, (std::vector<std::string>{"first", "blend", "out"}));
  }

  // A transient goes back to the pool after its last pass; the next pass
  // (another eye) asking for the same description gets the same texture.
  void transientsArePooledAcrossPassesAndFrames() {
    r_.makeCurrent();
    ResourcePool pool;
    GLuint left = 0, right = 0, nextFrame = 0;
    {
      FrameGraph g(pool);
      consumer(g, "left_out", producer(g, "left", "color[left]", nullptr), nullptr, &left);
      consumer(g, "right_out", producer(g, "right", "color[right]", nullptr), nullptr, &right);
      g.execute();
    }
    QVERIFY(left != 0);
    QCOMPARE(right, left);
    QCOMPARE(pool.registry().size(), size_t(1));
    pool.endFrame();
    {
      FrameGraph g(pool);
      consumer(g, "out", producer(g, "p", "color", nullptr), nullptr, &nextFrame);
      g.execute();
    }
    QCOMPARE(nextFrame, left);  // the next frame reuses it too
    pool.endFrame();
    // A frame that does not use it: freed at its end.
    {
      FrameGraph g(pool);
      g.execute();
    }
    pool.endFrame();
    QCOMPARE(pool.registry().size(), size_t(0));
    QCOMPARE(pool.bytes(), size_t(0));
  }

  void keptResourcesOutliveTheFrame() {
    r_.makeCurrent();
    ResourcePool pool;
    auto g = std::make_unique<FrameGraph>(pool);
    const TextureRef t = producer(*g, "p", "kept", nullptr);
    g->keep(t);
    g->execute();
    QVERIFY(g->keptTexture(t) != 0);
    QVERIFY(ran(*g, "p"));  // kept counts as read
    const auto reg = pool.registry();
    QCOMPARE(reg.size(), size_t(1));
    QVERIFY(reg.front().inUse);
    g.reset();  // back to the pool
    QVERIFY(!pool.registry().front().inUse);
    QCOMPARE(pool.registry().front().bytes, kSmall.bytes());
    QCOMPARE(kSmall.bytes(), size_t(64 * 32 * 8));
  }

  // OpenGL's own reports reach the caller (the editor shows them in Messages).
  void glDebugOutputIsCollected() {
    r_.makeCurrent();
    r_.renderer().takeGlMessages();
    glBindTexture(GL_TEXTURE_2D, 0x7fffffff);  // not a texture name: GL_INVALID_OPERATION
    const std::vector<std::string> m = r_.renderer().takeGlMessages();
    QVERIFY2(!m.empty(), "no debug message for an invalid texture name");
    QVERIFY2(m.front().find("OpenGL error") == 0, m.front().c_str());
    glGetError();
  }

  // Timed passes (execute(true): `render --stats`, the editor's pass list,
  // the benchmarks) report each pass's own work. The reference is the same
  // draw timed here from the outside, between two glFinish. llvmpipe stamps
  // a timestamp when its rasteriser threads reach it in their tiles, so a
  // timestamp queued with the draws after it read as the end of their work:
  // a pass drawing into targets it did not clear got a fraction of a
  // millisecond (the terrain, 0.9 ms of about 550), and nothing got the rest.
  void timedPassesReportTheirOwnWork() {
    r_.makeCurrent();
    const GLuint program = busyProgram();
    QVERIFY(program);
    GLuint tex = 0, fbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA8, 512, 512);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, 512, 512);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(program);
    glBindVertexArray(vao);
    const GLint iterations = glGetUniformLocation(program, "uIterations");
    auto draw = [&] { glDrawArrays(GL_TRIANGLES, 0, 3); };
    // Timed from the outside: the least of three draws.
    auto reference = [&] {
      double best = 1e30;
      for (int i = 0; i < 3; ++i) {
        glFinish();
        const auto t0 = std::chrono::steady_clock::now();
        draw();
        glFinish();
        best = std::min(best, millisSince(t0));
      }
      return best;
    };
    // As many rounds as take 30 ms here, so that the work stands well above
    // the timers' resolution on any device (the first draw compiles).
    int n = 16;
    glProgramUniform1i(program, iterations, n);
    reference();
    double outside = 0.0;
    for (;; n *= 2) {
      glProgramUniform1i(program, iterations, n);
      outside = reference();
      if (outside >= 30.0 || n >= (1 << 20)) break;
    }
    // Through the graph, three times: the largest and least of each pass.
    double busyMax = 0.0, busyMin = 1e30, afterMin = 1e30;
    for (int run = 0; run < 3; ++run) {
      ResourcePool pool;
      FrameGraph g(pool);
      for (const char* name : {"busy", "after"})
        g.addPass<NoData>(
            name, [](PassBuilder& b, NoData&) { b.sideEffect(); },
            [&, busy = std::string(name) == "busy"](const NoData&, const PassResources&) {
              if (busy) draw();
            });
      g.execute(true);
      for (const PassRecord& rec : g.records()) {
        if (rec.name == "busy") {
          busyMax = std::max(busyMax, rec.gpuMs);
          busyMin = std::min(busyMin, rec.gpuMs);
        } else {
          afterMin = std::min(afterMin, rec.gpuMs);
        }
      }
    }
    qInfo("%d rounds: %.1f ms between two glFinish; the timed pass %.1f-%.1f ms, the pass after it from %.1f ms", n,
          outside, busyMin, busyMax, afterMin);
    QVERIFY2(busyMax >= 0.5 * outside, "the pass's timestamps missed most of its draw");
    QVERIFY2(busyMin <= 2.0 * outside + 5.0, "the pass's timestamps hold more than its draw");
    QVERIFY2(afterMin <= 0.2 * outside + 1.0, "the next pass was given the draw's time");
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    glDeleteProgram(program);
  }

  // The frame's GPU time (measureGpuTime: the editor's status bar), read
  // two frames late, is never longer than the wall time since that frame
  // began. A renderer's first frame once read 95 minutes on llvmpipe (its
  // timer's beginning never stamped), shown in the status bar.
  void frameGpuTimeIsNeverLongerThanTheFrames() {
    OffscreenRenderer fresh;  // its own context: the first frame is the one that went wrong
    std::string error;
    QVERIFY2(fresh.initialize(error), error.c_str());
    const render::RenderView v = render::frameBox(glm::dvec3(-5), glm::dvec3(5), 96, 64);
    render::RenderOptions o;
    o.measureGpuTime = true;
    const auto start = std::chrono::steady_clock::now();
    int known = 0;
    for (int f = 0; f < 6; ++f) {
      const render::FrameStats st = fresh.renderOnly(demo_, v, o);
      const double elapsed = millisSince(start);
      qInfo("frame %d: frame GPU time %.2f ms, %.1f ms since the first frame began", f, st.gpuMs, elapsed);
      QVERIFY2(st.gpuMs <= elapsed, "a frame's GPU time longer than all the frames together");
      known += st.gpuMs >= 0.0;
    }
    QVERIFY(known >= 2);  // read two frames late: frames 3 to 5 know one (the first may be dropped)
    r_.makeCurrent();
  }

  // ---- the renderer: optional passes and their memory -------------------------

  void msaaTargetsOnlyWithMsaa() {
    const render::RenderView v = render::frameBox(glm::dvec3(-5), glm::dvec3(5), 96, 64);
    scene::SceneState s = demo_;
    s.settings.antialiasing = scene::Antialiasing::None;
    render::FrameStats st;
    r_.render(s, v, false, &st);
    auto reg = r_.renderer().resourceRegistry();
    QCOMPARE(registryBytes(reg, "scene_color"), size_t(96 * 64 * 8));  // one sample
    QVERIFY(!has(passNames(st), "resolve"));
    QVERIFY(!has(passNames(st), "fxaa"));
    QCOMPARE(registryCount(reg, "ldr_color"), size_t(0));
    s.settings.antialiasing = scene::Antialiasing::Msaa4;
    r_.render(s, v, false, &st);
    reg = r_.renderer().resourceRegistry();
    QCOMPARE(registryBytes(reg, "scene_color"), size_t(96 * 64 * 8 * 4));  // four samples
    QVERIFY(has(passNames(st), "resolve"));
    QCOMPARE(registryCount(reg, "hdr_color"), size_t(1));
    s.settings.antialiasing = scene::Antialiasing::Fxaa;
    r_.render(s, v, false, &st);
    reg = r_.renderer().resourceRegistry();
    QVERIFY(has(passNames(st), "fxaa"));
    QCOMPARE(registryBytes(reg, "ldr_color"), size_t(96 * 64 * 4));
    // MSAA's targets went with the frame that stopped using them.
    QCOMPARE(registryBytes(reg, "scene_color"), size_t(96 * 64 * 8));
    QCOMPARE(registryCount(reg, "hdr_color"), size_t(0));
  }

  void terrainGridAndOverlayPassesOnlyWhenThere() {
    const render::RenderView v = render::frameBox(glm::dvec3(-5), glm::dvec3(5), 96, 64);
    scene::SceneState s = demo_;
    // The demo has a terrain: without its entities there is no terrain pass.
    render::FrameStats st;
    r_.render(s, v, false, &st);
    const bool demoHasTerrain = !s.terrains.empty();
    QCOMPARE(has(passNames(st), "terrain"), demoHasTerrain);
    for (auto& [id, e] : s.entities) e.terrain.reset();
    s.settings.showGrid = false;
    r_.render(s, v, false, &st);
    QVERIFY(!has(passNames(st), "terrain"));
    QVERIFY(!has(passNames(st), "grid"));
    QVERIFY(!has(passNames(st), "overlay"));
    QVERIFY(has(passNames(st), "opaque"));
    QVERIFY(has(passNames(st), "tonemap"));
  }

  // Both eyes in one frame: passes per eye, targets reused from eye to eye.
  void stereoFrameSharesPooledTargets() {
    r_.makeCurrent();
    const render::RenderView v = render::frameBox(glm::dvec3(-5), glm::dvec3(5), 96, 64);
    render::RenderView right = v;
    right.eye += right.right() * 0.065;
    OutputTargetPair out;
    out.make(96, 64);
    render::RenderOptions o;
    o.lodView = &v;
    const render::FrameStats st =
        r_.renderer().renderViews(demo_, {{v, out.fbo[0], "left"}, {right, out.fbo[1], "right"}}, o);
    const auto names = passNames(st);
    QVERIFY(has(names, "opaque[left]") && has(names, "opaque[right]"));
    QVERIFY(has(names, "tonemap[left]") && has(names, "tonemap[right]"));
    // One scene colour texture served both eyes.
    QCOMPARE(registryCount(r_.renderer().resourceRegistry(), "scene_color"), size_t(1));
    out.release();
  }

 private:
  struct OutputTargetPair {
    GLuint fbo[2] = {0, 0}, rb[2] = {0, 0};
    void make(int w, int h) {
      glCreateRenderbuffers(2, rb);
      glCreateFramebuffers(2, fbo);
      for (int i = 0; i < 2; ++i) {
        glNamedRenderbufferStorage(rb[i], GL_RGBA8, w, h);
        glNamedFramebufferRenderbuffer(fbo[i], GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[i]);
      }
    }
    void release() {
      glDeleteFramebuffers(2, fbo);
      glDeleteRenderbuffers(2, rb);
    }
  };
};

QTEST_GUILESS_MAIN(TestFrameGraph)
#include "test_frame_graph.moc"
