// Stereo: off-axis frusta meet at the convergence distance, interaxial 0
// gives identical eyes, pivots, toe-in's warning, the comfort check, layout
// sizes and pixels, anaglyph colours.
#include <QtTest>

#include <cmath>
#include <random>

#include "core/srgb.h"
#include "sequencer/anaglyph.h"
#include "sequencer/comfort_check.h"
#include "sequencer/stereo_layout.h"
#include "sequencer/stereo_rig.h"

using namespace hs::sequencer;
using hs::Image;
using hs::ImageView;

namespace {

CameraModel randomCamera(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), fov(20.0, 90.0), asp(0.5, 3.0);
  std::normal_distribution<double> n(0.0, 1.0);
  CameraModel c;
  c.position = glm::dvec3(u(rng), u(rng), u(rng)) * 5e5;  // up to UTM-like magnitudes
  c.orientation = glm::normalize(glm::dquat(n(rng), n(rng), n(rng), n(rng)));
  c.fovY = glm::radians(fov(rng));
  c.aspect = asp(rng);
  return c;
}

Image solid8(int w, int h, uint8_t r, uint8_t g, uint8_t b) {
  Image img = Image::make8(w, h);
  for (size_t i = 0; i < img.pixelCount(); ++i) {
    img.rgba8[i * 4] = r;
    img.rgba8[i * 4 + 1] = g;
    img.rgba8[i * 4 + 2] = b;
    img.rgba8[i * 4 + 3] = 255;
  }
  return img;
}

Image pattern8(int w, int h, int seed) {
  Image img = Image::make8(w, h);
  for (size_t i = 0; i < img.rgba8.size(); ++i) img.rgba8[i] = uint8_t((i * 31 + size_t(seed) * 17) & 255);
  return img;
}

}  // namespace

class TestStereo : public QObject {
  Q_OBJECT

 private slots:
  void offAxisFrustaMeetAtConvergence() {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0), b(0.01, 2.0), c(0.5, 500.0);
    double worst = 0.0;
    for (int trial = 0; trial < 500; ++trial) {
      const CameraModel mono = randomCamera(rng);
      StereoRig rig;
      rig.interaxial = b(rng);
      rig.convergence = c(rng);
      rig.pivot = RigPivot(rng() % 3);
      const StereoCameras eyes = stereoCameras(mono, rig);
      QVERIFY(eyes.warnings.empty());
      // Points on the zero-parallax plane (view depth C from the eyes),
      // anywhere in the picture, land on the same pixel in both eyes.
      const glm::dvec3 centre = 0.5 * (eyes.left.position + eyes.right.position);
      for (int i = 0; i < 10; ++i) {
        const double t = std::tan(mono.fovY / 2.0) * rig.convergence;
        const glm::dvec3 p = centre + mono.orientation * glm::dvec3(u(rng) * t * mono.aspect, u(rng) * t, -rig.convergence);
        const auto l = eyes.left.projectPixel(p, 1920, 1080), r = eyes.right.projectPixel(p, 1920, 1080);
        QVERIFY(l && r);
        worst = std::max(worst, glm::length(*l - *r));
      }
      // Off the plane, parallax follows (b / (2 tan(fovX/2))) (1/C - 1/Z).
      const double tanX = std::tan(mono.fovY / 2.0) * mono.aspect;
      for (double z : {rig.convergence * 0.3, rig.convergence * 3.0, std::numeric_limits<double>::infinity()}) {
        const double expected = rig.interaxial / (2.0 * tanX) * (1.0 / rig.convergence - 1.0 / z);
        QVERIFY(std::abs(midlineParallax(eyes, z) - expected) < 1e-9 + 1e-9 * std::abs(expected));
      }
    }
    qInfo("largest pixel difference of points on the convergence plane: %.3g px", worst);
    QVERIFY(worst < 1e-6);
  }

  void projectionMatrixAgreesWithProjection() {
    std::mt19937_64 rng(5);
    const CameraModel mono = randomCamera(rng);
    StereoRig rig;
    rig.interaxial = 0.5;
    rig.convergence = 20.0;
    const StereoCameras eyes = stereoCameras(mono, rig);
    for (const CameraModel* cam : {&eyes.left, &eyes.right}) {
      const glm::dvec3 p = cam->position + cam->forward() * 37.0 + cam->right() * 3.0 + cam->up() * -2.0;
      const glm::dvec4 clip = cam->projection() * cam->view() * glm::dvec4(p, 1.0);
      const glm::dvec2 ndc = *cam->projectNdc(p);
      QVERIFY(std::abs(clip.x / clip.w - ndc.x) < 1e-9);
      QVERIFY(std::abs(clip.y / clip.w - ndc.y) < 1e-9);
      const double depth = clip.z / clip.w;  // reversed Z: 1 at near, 0 at far
      QVERIFY(depth > 0.0 && depth < 1.0);
      // unproject() is projectNdc()'s inverse.
      QVERIFY(glm::length(cam->unproject(ndc, glm::dot(p - cam->position, cam->forward())) - p) < 1e-6);
    }
  }

  void zeroInteraxialGivesIdenticalEyes() {
    std::mt19937_64 rng(2);
    for (StereoMode mode : {StereoMode::OffAxis, StereoMode::Parallel, StereoMode::ToeIn})
      for (RigPivot pivot : {RigPivot::Left, RigPivot::Centre, RigPivot::Right}) {
        const CameraModel mono = randomCamera(rng);
        const StereoCameras eyes = stereoCameras(mono, StereoRig{mode, 0.0, 10.0, pivot});
        QVERIFY(eyes.left.position == eyes.right.position);
        QVERIFY(eyes.left.orientation == eyes.right.orientation);
        QCOMPARE(eyes.left.ndcShiftX, eyes.right.ndcShiftX);
        QVERIFY(eyes.left.projection() == eyes.right.projection());
        QVERIFY(eyes.left.position == mono.position);
        QVERIFY(eyes.warnings.empty());
      }
  }

  void pivotsPlaceTheEyes() {
    CameraModel mono;
    mono.position = {10, 20, 30};
    StereoRig rig;
    rig.interaxial = 0.2;
    rig.pivot = RigPivot::Left;
    QVERIFY(stereoCameras(mono, rig).left.position == mono.position);
    QVERIFY(glm::length(stereoCameras(mono, rig).right.position - (mono.position + mono.right() * 0.2)) < 1e-12);
    rig.pivot = RigPivot::Right;
    QVERIFY(stereoCameras(mono, rig).right.position == mono.position);
    rig.pivot = RigPivot::Centre;
    const auto c = stereoCameras(mono, rig);
    QVERIFY(glm::length(0.5 * (c.left.position + c.right.position) - mono.position) < 1e-12);
    // The zero-parallax window is centred between the eyes for every pivot.
    for (RigPivot p : {RigPivot::Left, RigPivot::Centre, RigPivot::Right}) {
      rig.pivot = p;
      QVERIFY(std::abs(midlineParallax(stereoCameras(mono, rig), rig.convergence)) < 1e-12);
    }
  }

  void parallelAndToeIn() {
    CameraModel mono;
    StereoRig rig;
    rig.interaxial = 0.065;
    rig.convergence = 5.0;
    rig.mode = StereoMode::Parallel;
    const auto par = stereoCameras(mono, rig);
    QCOMPARE(par.left.ndcShiftX, 0.0);
    QVERIFY(std::abs(midlineParallax(par, std::numeric_limits<double>::infinity())) < 1e-15);
    QVERIFY(midlineParallax(par, 5.0) < 0.0);  // everything in front of the screen
    rig.mode = StereoMode::ToeIn;
    const auto toe = stereoCameras(mono, rig);
    QVERIFY(std::abs(midlineParallax(toe, 5.0)) < 1e-12);  // the axes cross at C
    QCOMPARE(toe.warnings.size(), size_t(1));
    QVERIFY(toe.warnings[0].find("vertical parallax") != std::string::npos);
    qInfo("%s", toe.warnings[0].c_str());
    // A corner of the frame at the convergence distance has vertical parallax.
    const glm::dvec3 corner(std::tan(mono.fovY / 2) * mono.aspect * 5.0 * 0.9, std::tan(mono.fovY / 2) * 5.0 * 0.9, -5.0);
    QVERIFY(std::abs(toe.left.projectNdc(corner)->y - toe.right.projectNdc(corner)->y) > 1e-5);
    QVERIFY(std::abs(par.left.projectNdc(corner)->y - par.right.projectNdc(corner)->y) < 1e-15);
  }

  void comfortCheckFromDepth() {
    CameraModel mono;
    mono.fovY = glm::radians(40.0);
    mono.aspect = 16.0 / 9.0;
    StereoRig rig;
    rig.interaxial = 0.3;
    rig.convergence = 30.0;
    const StereoCameras eyes = stereoCameras(mono, rig);
    const double tanX = std::tan(mono.fovY / 2) * mono.aspect;
    auto expected = [&](double z) { return rig.interaxial / (2 * tanX) * (1 / rig.convergence - 1 / z); };
    // A 64x36 linear depth image: ground from 12 m to 300 m, sky on top.
    const int w = 64, h = 36;
    std::vector<float> depth(size_t(w * h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        depth[size_t(y * w + x)] = y < 10 ? std::numeric_limits<float>::infinity() : float(300.0 - (y - 10) * (288.0 / 25.0));
    DepthImage img{w, h, depth.data(), DepthKind::Linear};
    ComfortResult r = checkComfort(eyes, img, nullptr);
    QVERIFY(r.hasPixels);
    QVERIFY(std::abs(r.nearestDepth - 12.0) < 1e-4);
    QVERIFY(std::isinf(r.farthestDepth));
    QVERIFY(std::abs(r.nearestParallax - expected(12.0)) < 1e-7);
    QVERIFY(std::abs(r.farthestParallax - expected(INFINITY)) < 1e-12);
    qInfo("nearest %.3f%%, farthest %.3f%% (sky) -> %s", r.nearestParallax * 100, r.farthestParallax * 100,
          r.withinBudget ? "within budget" : r.message.c_str());
    QVERIFY(!r.withinBudget);  // 0.3 m converged at 30 m brings 12 m past -1%
    QVERIFY(r.message.find("nearest parallax") != std::string::npos);
    // Ignoring the sky, the far end is 300 m.
    ComfortOptions noSky;
    noSky.skyAtInfinity = false;
    r = checkComfort(eyes, img, nullptr, noSky);
    QVERIFY(std::abs(r.farthestParallax - expected(300.0)) < 1e-7);
    // The same from a reversed-Z buffer.
    std::vector<float> rz(depth.size());
    const double n = 0.1, f = 50000.0;
    for (size_t i = 0; i < depth.size(); ++i)
      rz[i] = std::isinf(depth[i]) ? 0.0f : float(n * (f - double(depth[i])) / ((f - n) * double(depth[i])));
    QVERIFY(std::abs(linearDepthFromReversedZ(n * (f - 12.0) / ((f - n) * 12.0), n, f) - 12.0) < 1e-9);
    const ComfortResult rr = checkComfort(eyes, DepthImage{w, h, rz.data(), DepthKind::ReversedZ, n, f}, nullptr);
    QVERIFY(std::abs(rr.nearestParallax - expected(12.0)) < 1e-5);
    // A suggested rig fits the range to the budget exactly.
    const auto fit = suggestRig(12.0, 300.0, tanX);
    QVERIFY(fit);
    const StereoCameras fitted = stereoCameras(mono, *fit);
    QVERIFY(std::abs(midlineParallax(fitted, 12.0) - (-0.01)) < 1e-12);
    QVERIFY(std::abs(midlineParallax(fitted, 300.0) - 0.02) < 1e-12);
    qInfo("suggested rig for 12..300 m: interaxial %.3f m, convergence %.2f m", fit->interaxial, fit->convergence);
    const auto fitInf = suggestRig(12.0, INFINITY, tanX);
    QVERIFY(std::abs(midlineParallax(stereoCameras(mono, *fitInf), INFINITY) - 0.02) < 1e-12);
    // Frames outside the budget are listed.
    std::vector<FrameComfort> frames = {{10, r}, {11, rr}};
    frames[0].result.withinBudget = true;
    QCOMPARE(framesOutsideBudget(frames), (std::vector<int64_t>{11}));
  }

  void toeInComfortReprojectsEveryPixel() {
    // The per-pixel reprojection (toe-in's path) agrees with the closed form
    // on an off-axis rig, which checks the reprojection itself.
    CameraModel mono;
    StereoRig rig;
    rig.interaxial = 0.1;
    rig.convergence = 8.0;
    StereoCameras eyes = stereoCameras(mono, rig);
    const int w = 48, h = 27;
    std::vector<float> depth(size_t(w * h));
    for (size_t i = 0; i < depth.size(); ++i) depth[i] = float(3.0 + double(i % 97));
    const DepthImage img{w, h, depth.data(), DepthKind::Linear};
    const ComfortResult closed = checkComfort(eyes, img, &img);
    eyes.mode = StereoMode::ToeIn;  // force the reprojection path
    const ComfortResult reproj = checkComfort(eyes, img, &img);
    QVERIFY(std::abs(closed.nearestParallax - reproj.nearestParallax) < 1e-9);
    QVERIFY(std::abs(closed.farthestParallax - reproj.farthestParallax) < 1e-9);
    // A real toe-in rig: the centre of the convergence distance has zero parallax.
    rig.mode = StereoMode::ToeIn;
    const StereoCameras toe = stereoCameras(mono, rig);
    std::vector<float> flat(size_t(w * h), 8.0f);
    const ComfortResult t = checkComfort(toe, DepthImage{w, h, flat.data(), DepthKind::Linear}, nullptr);
    qInfo("toe-in, a flat wall at the convergence distance: parallax from %.4f%% to %.4f%%", t.nearestParallax * 100,
          t.farthestParallax * 100);
    // Zero at the centre; towards the edges the wall falls behind toe-in's
    // curved zero-parallax surface (which bows towards the camera).
    QVERIFY(std::abs(t.nearestParallax) < 1e-5);
    QVERIFY(t.farthestParallax > 1e-3 && t.farthestParallax < 0.01);
  }

  void layoutSizes() {
    const int w = 1920, h = 1080;
    QVERIFY(layoutFrameSize(StereoLayout::SideBySide, w, h) == glm::ivec2(3840, 1080));
    QVERIFY(layoutFrameSize(StereoLayout::SideBySideSqueezed, w, h) == glm::ivec2(1920, 1080));
    QVERIFY(layoutFrameSize(StereoLayout::TopBottom, w, h) == glm::ivec2(1920, 2160));
    QVERIFY(layoutFrameSize(StereoLayout::TopBottomSqueezed, w, h) == glm::ivec2(1920, 1080));
    QVERIFY(layoutFrameSize(StereoLayout::Anaglyph, w, h) == glm::ivec2(1920, 1080));
    QVERIFY(layoutFrameSize(StereoLayout::Separate, w, h) == glm::ivec2(1920, 1080));
    QVERIFY(layoutFrameSize(StereoLayout::Mono, w, h) == glm::ivec2(1920, 1080));
    QCOMPARE(layoutFilesPerFrame(StereoLayout::Separate), 2);
    QVERIFY(!layoutRendersBothEyes(StereoLayout::Mono));
    // The real thing at full size.
    const Image l = solid8(w, h, 10, 20, 30), r = solid8(w, h, 200, 100, 50);
    const auto sbs = composeLayout(StereoLayout::SideBySide, l, r);
    QCOMPARE(sbs.size(), size_t(1));
    QCOMPARE(sbs[0].width, 3840);
    QCOMPARE(sbs[0].height, 1080);
    for (StereoLayout layout : {StereoLayout::SideBySideSqueezed, StereoLayout::TopBottom, StereoLayout::TopBottomSqueezed,
                                StereoLayout::Anaglyph, StereoLayout::Mono, StereoLayout::Separate}) {
      const auto out = composeLayout(layout, l, r);
      const glm::ivec2 size = layoutFrameSize(layout, w, h);
      QCOMPARE(int(out.size()), layoutFilesPerFrame(layout));
      for (const Image& img : out) {
        QCOMPARE(img.width, size.x);
        QCOMPARE(img.height, size.y);
      }
    }
    for (const char* name : {"sbs", "sbs-half", "tb", "tb-half", "separate", "anaglyph", "mono"})
      QVERIFY(layoutName(*layoutFromName(name)) == std::string(name));
  }

  void layoutPixels() {
    const int w = 8, h = 4;
    const Image l = pattern8(w, h, 1), r = pattern8(w, h, 2);
    const Image sbs = composeLayout(StereoLayout::SideBySide, l, r)[0];
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 4; ++c) {
          QCOMPARE(sbs.rgba8[size_t((y * 2 * w + x) * 4 + c)], l.rgba8[size_t((y * w + x) * 4 + c)]);
          QCOMPARE(sbs.rgba8[size_t((y * 2 * w + w + x) * 4 + c)], r.rgba8[size_t((y * w + x) * 4 + c)]);
        }
    const Image tb = composeLayout(StereoLayout::TopBottom, l, r)[0];
    QVERIFY(std::equal(l.rgba8.begin(), l.rgba8.end(), tb.rgba8.begin()));
    QVERIFY(std::equal(r.rgba8.begin(), r.rgba8.end(), tb.rgba8.begin() + long(l.rgba8.size())));
    QVERIFY(composeLayout(StereoLayout::Mono, l, r)[0] == l);
    const auto sep = composeLayout(StereoLayout::Separate, l, r);
    QVERIFY(sep[0] == l && sep[1] == r);
    // Squeezing a flat colour keeps it; black|white pairs average in linear light.
    const Image flat = composeLayout(StereoLayout::SideBySideSqueezed, solid8(w, h, 90, 90, 90), solid8(w, h, 200, 10, 0))[0];
    QCOMPARE(flat.rgba8[0], uint8_t(90));
    QCOMPARE(flat.rgba8[size_t((w / 2) * 4)], uint8_t(200));
    QCOMPARE(flat.rgba8[size_t((w / 2) * 4 + 1)], uint8_t(10));
    Image stripes = Image::make8(w, h);
    for (size_t i = 0; i < stripes.pixelCount(); ++i) {
      const uint8_t v = (i % 2) ? 255 : 0;
      stripes.rgba8[i * 4] = stripes.rgba8[i * 4 + 1] = stripes.rgba8[i * 4 + 2] = v;
      stripes.rgba8[i * 4 + 3] = 255;
    }
    const Image half = composeLayout(StereoLayout::SideBySideSqueezed, stripes, stripes)[0];
    QCOMPARE(int(half.rgba8[0]), int(hs::linearToSrgb8(0.5f)));  // 188, not 128
    QCOMPARE(int(half.rgba8[0]), 188);
    const Image tbh = composeLayout(StereoLayout::TopBottomSqueezed, solid8(w, h, 1, 2, 3), solid8(w, h, 4, 5, 6))[0];
    QCOMPARE(tbh.rgba8[0], uint8_t(1));
    QCOMPARE(tbh.rgba8[size_t((h - 1) * w * 4)], uint8_t(4));
    // Odd widths: the halves still fill the frame.
    const Image odd = composeLayout(StereoLayout::SideBySideSqueezed, solid8(7, 3, 50, 50, 50), solid8(7, 3, 60, 60, 60))[0];
    QCOMPARE(odd.width, 7);
    QCOMPARE(odd.rgba8[size_t(6 * 4)], uint8_t(60));
    // Float images.
    Image lf = Image::makeF(4, 2), rf = Image::makeF(4, 2);
    std::fill(lf.rgbaF.begin(), lf.rgbaF.end(), 2.5f);
    std::fill(rf.rgbaF.begin(), rf.rgbaF.end(), 0.25f);
    const Image sbsf = composeLayout(StereoLayout::SideBySide, lf, rf)[0];
    QCOMPARE(sbsf.rgbaF[0], 2.5f);
    QCOMPARE(sbsf.rgbaF[size_t(4 * 4)], 0.25f);
    QCOMPARE(composeLayout(StereoLayout::SideBySideSqueezed, lf, rf)[0].rgbaF[0], 2.5f);
    // Mismatched eyes give nothing rather than garbage.
    QVERIFY(composeLayout(StereoLayout::SideBySide, l, solid8(w + 1, h, 0, 0, 0)).empty());
  }

  void anaglyphColours() {
    const Image white = solid8(4, 4, 255, 255, 255), black = solid8(4, 4, 0, 0, 0);
    const Image a = makeAnaglyph(white, white);
    QVERIFY(std::abs(int(a.rgba8[0]) - 255) <= 1 && std::abs(int(a.rgba8[1]) - 255) <= 1 && std::abs(int(a.rgba8[2]) - 255) <= 1);
    // Left eye only: mostly red; right eye only: cyan.
    const Image leftOnly = makeAnaglyph(white, black);
    QVERIFY(leftOnly.rgba8[0] > 200 && leftOnly.rgba8[1] == 0 && leftOnly.rgba8[2] == 0);
    const Image rightOnly = makeAnaglyph(black, white);
    QVERIFY(rightOnly.rgba8[0] == 0 && rightOnly.rgba8[1] > 200 && rightOnly.rgba8[2] > 200);
    // Colour method: channels copied.
    const Image c = makeAnaglyph(solid8(2, 2, 10, 20, 30), solid8(2, 2, 40, 50, 60), AnaglyphMethod::Color);
    QCOMPARE(c.rgba8[0], uint8_t(10));
    QCOMPARE(c.rgba8[1], uint8_t(50));
    QCOMPARE(c.rgba8[2], uint8_t(60));
    // Rows sum to about 1: grey stays grey.
    for (AnaglyphMethod m : {AnaglyphMethod::Dubois, AnaglyphMethod::Color, AnaglyphMethod::Gray}) {
      const AnaglyphMatrices& mx = anaglyphMatrices(m);
      for (int r = 0; r < 3; ++r) {
        double sum = 0;
        for (int k = 0; k < 3; ++k) sum += mx.left[r][k] + mx.right[r][k];
        QVERIFY(std::abs(sum - 1.0) < 0.002);
      }
    }
  }
};

QTEST_APPLESS_MAIN(TestStereo)
#include "test_sequencer_stereo.moc"
