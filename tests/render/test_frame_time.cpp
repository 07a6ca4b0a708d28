// The frame's time (scene::SceneTime -> FrameBlock.time): animatedState
// stamps the time it evaluated, the renderer uploads it, and a shader that
// reads it gives the same pixels for frame 120 rendered alone and after
// frames 100-119 (nothing of earlier frames leaks into a frame: DESIGN.md,
// "Time and determinism"). The probe shader is built here from the
// renderer's own frame_blocks.glsl, so it reads the block as every renderer
// shader does.
#include <QtTest>

#include <cmath>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "gl_test_program.h"
#include "render/gl/shader_library.h"
#include "render/offscreen_renderer.h"
#include "scene/animation.h"
#include "scene/demo_scene.h"

using namespace hs;
using render::OffscreenRenderer;

namespace {

GLuint buildProbe(std::string& error) {
  std::string block;
  if (!render::gl::expandShaderInclude("frame_blocks.glsl", block, error)) return 0;
  // Time-dependent noise: each pixel a hash of its position and the frame
  // number, modulated by fract(t); alpha carries the frame number.
  const std::string fs = "#version 450 core\n" + block +
                         "\nout vec4 color;\n"
                         "uint hash(uint x) { x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; "
                         "return x ^ (x >> 16); }\n"
                         "void main() {\n"
                         "  uvec2 p = uvec2(gl_FragCoord.xy);\n"
                         "  uint h = hash(p.x + 977u * p.y + 7919u * uint(frame.time.y));\n"
                         "  color = vec4(float(h & 0xffffu) / 65535.0, frame.time.z, frame.time.x, frame.time.y);\n"
                         "}\n";
  return test::linkProgram({{GL_VERTEX_SHADER, test::kFullscreenTriangleVs}, {GL_FRAGMENT_SHADER, fs}}, &error);
}

}  // namespace

class TestFrameTime : public QObject {
  Q_OBJECT
  scene::SceneState demo_;
  sequencer::CompiledSequence compiled_;

  // Renders the demo at frame `f` with `r`, then runs the probe over the
  // frame block the renderer left bound; returns the probe's pixels.
  std::vector<float> frameProbe(OffscreenRenderer& r, int64_t f) {
    const scene::SceneState s = scene::animatedState(demo_, compiled_, double(f) / demo_.sequence.rate.fps());
    r.render(s, render::frameBox(glm::dvec3(-5), glm::dvec3(5), 64, 48));
    r.makeCurrent();
    std::string error;
    const GLuint prog = buildProbe(error);
    if (!prog) qFatal("the probe does not build: %s", error.c_str());
    GLuint tex = 0, fbo = 0, vao = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA32F, 32, 16);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
    glCreateVertexArrays(1, &vao);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, 32, 16);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(prog);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<float> px(32 * 16 * 4);
    glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, GLsizei(px.size() * sizeof(float)), px.data());
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    glDeleteProgram(prog);
    return px;
  }

 private slots:
  void initTestCase() {
    std::string error;
    std::optional<scene::SceneState> d = scene::buildDemoScene(error);
    QVERIFY2(d, error.c_str());
    demo_ = std::move(*d);
    compiled_ = scene::compileSequence(demo_);
  }

  void animatedStateStampsItsTime() {
    const double fps = demo_.sequence.rate.fps();
    const scene::SceneState s = scene::animatedState(demo_, compiled_, 120.0 / fps);
    QCOMPARE(s.time.frame, int64_t(120));
    QCOMPARE(s.time.seconds, 120.0 / fps);
    QCOMPARE(s.time.fps, fps);
    QCOMPARE(demo_.time.seconds, 0.0);  // the document itself is at t = 0
  }

  void frameAloneEqualsFrameAfterOthers() {
    std::vector<float> alone, after, previous;
    {
      OffscreenRenderer r;
      std::string error;
      QVERIFY2(r.initialize(error), error.c_str());
      alone = frameProbe(r, 120);
    }
    {
      OffscreenRenderer r;
      std::string error;
      QVERIFY2(r.initialize(error), error.c_str());
      for (int64_t f = 100; f < 120; ++f) previous = frameProbe(r, f);
      after = frameProbe(r, 120);
    }
    QCOMPARE(alone.size(), after.size());
    qInfo("frame 120 probe: seconds %g frame %g fract %g; frame 119's frame %g", double(after[2]), double(after[3]),
          double(after[1]), double(previous[3]));
    QVERIFY(alone == after);  // bit for bit
    // The probe really sees the time: frame 119 differs, and the block
    // holds frame 120's number and seconds.
    QVERIFY(previous != after);
    const double fps = demo_.sequence.rate.fps();
    QCOMPARE(after[3], 120.0f);
    QCOMPARE(after[2], float(120.0 / fps));
    QCOMPARE(after[1], float(120.0 / fps - std::floor(120.0 / fps)));
  }
};

QTEST_GUILESS_MAIN(TestFrameTime)
#include "test_frame_time.moc"
