#include "render/stereo_frame_source.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <set>

#include <epoxy/gl.h>

#include "core/srgb.h"
#include "render/auto_exposure.h"
#include "render/output_target.h"
#include "render/pixel_readback.h"
#include "render/stereo_views.h"
#include "scene/animation.h"
#include "scene/camera_cuts_check.h"

namespace hs::render {

namespace {

enum class PixelKind { Display8, Display16, LinearFloat };

size_t bytesPerPixel(PixelKind k) {
  switch (k) {
    case PixelKind::Display8: return 4;
    case PixelKind::Display16: return 8;
    case PixelKind::LinearFloat: return 16;
  }
  return 4;
}

// GL rows run bottom-up, images top-down.
hs::Image imageFrom(const uint8_t* src, int w, int h, PixelKind kind) {
  const size_t rowPixels = size_t(w);
  switch (kind) {
    case PixelKind::Display8: {
      hs::Image img = hs::Image::make8(w, h);
      copyRowsFlipped(src, img.rgba8.data(), rowPixels * 4, size_t(h));
      return img;
    }
    case PixelKind::Display16: {
      // 16-bit sRGB display values to linear float: the writer encodes them
      // back (16-bit PNG) with nothing lost, and layouts mix in linear light.
      hs::Image img = hs::Image::makeF(w, h);
      for (int y = 0; y < h; ++y) {
        const auto* row = reinterpret_cast<const uint16_t*>(src + size_t(h - 1 - y) * rowPixels * 8);
        float* dst = img.rgbaF.data() + size_t(y) * rowPixels * 4;
        for (size_t i = 0; i < rowPixels * 4; ++i)
          dst[i] = (i % 4) == 3 ? 1.0f : srgbFloatToLinear(float(row[i]) / 65535.0f);
      }
      return img;
    }
    case PixelKind::LinearFloat: {
      hs::Image img = hs::Image::makeF(w, h);
      copyRowsFlipped(src, img.rgbaF.data(), rowPixels * 16, size_t(h));
      return img;
    }
  }
  return {};
}

std::vector<float> depthFrom(const uint8_t* src, int w, int h) {
  std::vector<float> out(size_t(w) * size_t(h));
  copyRowsFlipped(src, out.data(), size_t(w) * sizeof(float), size_t(h));
  return out;
}

}  // namespace

struct StereoFrameSource::Impl {
  OffscreenRenderer& offscreen;
  const scene::SceneState base;  // a copy: meshes are shared, so it costs the entity table only
  StereoFrameOptions options;
  sequencer::CompiledSequence compiled;
  scene::EntityId camera = scene::kNoEntity;
  bool followCuts = false;  // no camera given and the scene has cuts
  std::string cutsProblem;  // why they cannot be rendered ("" when sound)

  // The output framebuffer the renderer tone-maps into, per eye size.
  OutputTarget output[2];  // one per view: both eyes render in one frame
  OutputTarget groupOutput[2][2];  // a transition's two shots, each tone mapped alone too
  AutoExposure exposure;           // its probes are kept through the run (post.auto_exposure)

  struct Slot {
    PixelReadback buffer;
    int64_t frame = -1;
    int views = 0;          // 1 (mono) or 2 (eyes)
    int depthBase = 0;      // the renderer's kept view of view 0's depth (a transition: the stronger shot's)
    bool duplicate = false; // a mono camera in a stereo layout: the one view is both eyes
    PixelKind kind = PixelKind::Display8;
    int width = 0, height = 0;
    bool depth = false;
    sequencer::StereoCameras eyes;
  };
  Slot slots[2];
  int64_t begun = 0, finished = 0;

  std::vector<sequencer::FrameComfort> comfort;
  std::vector<std::string> warnings;
  std::set<std::string> seenWarnings;
  double waitSeconds = 0.0;

  Impl(OffscreenRenderer& r, const scene::SceneState& s, const StereoFrameOptions& o)
      : offscreen(r), base(s), options(o), compiled(scene::compileSequence(s)) {
    camera = o.camera != scene::kNoEntity ? o.camera : shotCamera(s);
    followCuts = o.camera == scene::kNoEntity && !s.sequence.cuts.empty();
    if (followCuts) cutsProblem = scene::cutsProblem(s);
    for (const std::string& p : compiled.problems()) warn(p);
  }

  RenderOptions renderOptions(const Slot& slot, const RenderView& lodView) const {
    RenderOptions ro;
    ro.lodView = &lodView;  // both eyes: their camera's levels of detail
    ro.showGrid = options.showGrid;
    ro.keepHdr = slot.kind == PixelKind::LinearFloat;
    ro.keepDepth = slot.depth;
    return ro;
  }
  static const char* eyeName(size_t count, size_t i) { return count == 2 ? (i == 0 ? "left" : "right") : ""; }

  void warn(const std::string& w) {
    if (seenWarnings.insert(w).second) warnings.push_back(w);
  }

  size_t colorBytes(const Slot& s) const { return size_t(s.width) * size_t(s.height) * bytesPerPixel(s.kind); }
  size_t depthBytes(const Slot& s) const { return size_t(s.width) * size_t(s.height) * 4; }
  // Layout of a slot's buffer: colour of each view, then depth of each view.
  size_t colorOffset(const Slot& s, int view) const { return colorBytes(s) * size_t(view); }
  size_t depthOffset(const Slot& s, int view) const {
    return colorBytes(s) * size_t(s.views) + depthBytes(s) * size_t(view);
  }

  // Renders the views of one frame (both eyes in one frame graph, so what
  // does not depend on the eye is done once) and queues their reads into
  // the slot's buffer. Levels of detail come from `lodView`.
  void renderViews(const scene::SceneState& state, const std::vector<RenderView>& views, Slot& slot,
                   const RenderView& lodView) {
    std::vector<ViewTarget> targets;
    for (size_t i = 0; i < views.size(); ++i) targets.push_back({views[i], output[i].fbo(), eyeName(views.size(), i)});
    offscreen.renderer().renderViews(state, targets, renderOptions(slot, lodView));
    slot.depthBase = 0;  // the frame's own views
    queueReads(slot, 0);
  }

  // A transition's frame: both shots' views (`shots[g]`, the same count
  // each) as two view groups of one frame, combined by the shot's
  // transition (its weights, or its pattern at its progress) into the
  // outputs; LODs per shot from its own mono view.
  void renderTransition(const scene::SceneState& state, const std::vector<RenderView> shots[2],
                        const RenderView* lodViews[2], const sequencer::Shot& shot, int64_t frame, Slot& slot) {
    const std::pair<float, float> weights = shot.weights();
    std::vector<ViewGroup> groups(2);
    for (size_t g = 0; g < 2; ++g) {
      for (size_t i = 0; i < shots[g].size(); ++i) {
        groupOutput[g][i].ensure(slot.width, slot.height, slot.kind == PixelKind::Display16 ? GL_RGBA16 : GL_RGBA8);
        groups[g].targets.push_back({shots[g][i], groupOutput[g][i].fbo(), eyeName(shots[g].size(), i)});
      }
      groups[g].lodView = lodViews[g];
    }
    GroupCombine combine = combineOf(shot, frame);
    for (size_t i = 0; i < shots[0].size(); ++i)
      combine.targets.push_back({shots[1][i], output[i].fbo(), eyeName(shots[0].size(), i)});
    RenderOptions ro = renderOptions(slot, *lodViews[0]);
    offscreen.renderer().renderGroups(state, groups, ro, &combine);
    // Kept views: each group's, then the combined ones. Depth (the comfort
    // check) is the stronger shot's: what a viewer's eyes converge on.
    const int views = int(shots[0].size());
    slot.depthBase = weights.second > weights.first ? views : 0;
    queueReads(slot, 2 * views);
  }

  // Queues the reads of the slot's colour (from the outputs, or the kept
  // HDR views from `hdrBase` on) and depth into its buffer.
  void queueReads(Slot& slot, int hdrBase) {
    slot.buffer.bindForPack();
    for (size_t i = 0; i < size_t(slot.views); ++i) {
      auto* colorAt = reinterpret_cast<void*>(colorOffset(slot, int(i)));
      if (slot.kind == PixelKind::LinearFloat) {
        offscreen.renderer().readHdrInto(colorAt, colorBytes(slot), size_t(hdrBase) + i);
      } else {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, output[i].fbo());
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glReadPixels(0, 0, slot.width, slot.height, GL_RGBA,
                     slot.kind == PixelKind::Display16 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_BYTE, colorAt);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
      }
      if (slot.depth)
        offscreen.renderer().readDepth(reinterpret_cast<void*>(depthOffset(slot, int(i))), size_t(slot.depthBase) + i);
    }
    PixelReadback::unbindPack();
  }
};

StereoFrameSource::StereoFrameSource(OffscreenRenderer& renderer, const scene::SceneState& scene,
                                     const StereoFrameOptions& options)
    : d_(std::make_unique<Impl>(renderer, scene, options)) {}

StereoFrameSource::~StereoFrameSource() {
  if (d_->offscreen.makeCurrent()) {
    for (auto& s : d_->slots) s.buffer.release();
    for (auto& o : d_->output) o.release();
    d_->exposure.release();
  }
}

int StereoFrameSource::framesInFlight() const { return std::clamp(d_->options.framesInFlight, 1, 2); }
scene::EntityId StereoFrameSource::camera() const { return d_->camera; }
const std::vector<sequencer::FrameComfort>& StereoFrameSource::comfort() const { return d_->comfort; }
const std::vector<std::string>& StereoFrameSource::warnings() const { return d_->warnings; }
double StereoFrameSource::readbackWaitSeconds() const { return d_->waitSeconds; }

bool StereoFrameSource::begin(const sequencer::FrameJob& job, std::string& error) {
  Impl& d = *d_;
  if (!d.offscreen.makeCurrent()) {
    error = "the headless OpenGL context could not be made current";
    return false;
  }
  if (!d.cutsProblem.empty()) {
    error = "the camera cuts cannot be rendered: " + d.cutsProblem;
    return false;
  }
  // The frame's shot: its cut's camera, or two during a transition.
  const std::optional<sequencer::Shot> shot =
      d.followCuts ? sequencer::shotAt(d.base.sequence.cuts, job.frame) : std::nullopt;
  const scene::EntityId camera = shot ? scene::EntityId(shot->camera) : d.camera;
  if (camera == scene::kNoEntity || !d.base.find(camera) || !d.base.find(camera)->camera) {
    error = "the scene has no camera to render through (add one, or name one with --camera)";
    return false;
  }
  std::vector<std::string> warnings;
  scene::SceneState state = scene::animatedState(d.base, d.compiled, job.time, &warnings);
  for (const std::string& w : warnings) d.warn(w);
  if (autoExposureOn(state, camera, shot)) {
    const StateAtTime stateAt = [&d](double t) { return scene::animatedState(d.base, d.compiled, t, nullptr); };
    state.settings.exposureEv100 =
        float(d.exposure.frameEv100(d.offscreen.renderer(), stateAt, state, camera, shot, d.base.sequence.rate,
                                    job.time, double(job.eyeWidth) / double(std::max(job.eyeHeight, 1))));
  }
  const EyeViews views = eyeViews(state, camera, job.eyeWidth, job.eyeHeight);
  std::optional<EyeViews> incoming;
  if (shot && shot->incoming) incoming = eyeViews(state, scene::EntityId(shot->incoming), job.eyeWidth, job.eyeHeight);

  Impl::Slot& slot = d.slots[d.begun % 2];
  slot.buffer.unmap();
  slot.frame = job.frame;
  slot.kind = job.floatPixels ? PixelKind::LinearFloat
                              : d.options.displayBits16 ? PixelKind::Display16 : PixelKind::Display8;
  slot.width = job.eyeWidth;
  slot.height = job.eyeHeight;
  // A transition between a stereo and a mono camera renders the mono one
  // for both eyes, so the two shots combine eye by eye.
  const bool twoViews = job.bothEyes && (views.stereo || (incoming && incoming->stereo));
  slot.views = twoViews ? 2 : 1;
  slot.duplicate = job.bothEyes && !twoViews;
  slot.depth = d.options.comfort.has_value();
  const bool incomingStronger = incoming && shot->weights().second > shot->weights().first;
  slot.eyes = incomingStronger ? incoming->eyes : views.eyes;
  for (int i = 0; i < slot.views; ++i)
    d.output[i].ensure(job.eyeWidth, job.eyeHeight, slot.kind == PixelKind::Display16 ? GL_RGBA16 : GL_RGBA8);
  slot.buffer.reserve(d.colorBytes(slot) * size_t(slot.views) + (slot.depth ? d.depthBytes(slot) * size_t(slot.views) : 0));
  auto viewsOf = [&](const EyeViews& e) {
    return twoViews ? (e.stereo ? std::vector<RenderView>{e.left, e.right} : std::vector<RenderView>{e.mono, e.mono})
                    : std::vector<RenderView>{e.mono};
  };
  if (incoming) {
    const std::vector<RenderView> shots[2] = {viewsOf(views), viewsOf(*incoming)};
    const RenderView* lods[2] = {&views.mono, &incoming->mono};
    d.renderTransition(state, shots, lods, *shot, job.frame, slot);
  } else {
    d.renderViews(state, viewsOf(views), slot, views.mono);
  }
  slot.buffer.fence();
  ++d.begun;
  const GLenum err = glGetError();
  if (err != GL_NO_ERROR) {
    error = "OpenGL error " + std::to_string(err) + " while rendering frame " + std::to_string(job.frame);
    return false;
  }
  return true;
}

bool StereoFrameSource::finish(const sequencer::FrameJob& job, sequencer::EyeImages& out, std::string& error) {
  Impl& d = *d_;
  if (d.finished >= d.begun) {
    error = "finish() without a frame begun";
    return false;
  }
  Impl::Slot& slot = d.slots[d.finished % 2];
  if (slot.frame != job.frame) {
    error = "frames finished out of order (" + std::to_string(job.frame) + " after " + std::to_string(slot.frame) + ")";
    return false;
  }
  d.offscreen.makeCurrent();
  const auto t0 = std::chrono::steady_clock::now();
  const uint8_t* p = slot.buffer.map();
  d.waitSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!p) {
    error = "could not map the pixel buffer of frame " + std::to_string(job.frame);
    return false;
  }
  out.left = imageFrom(p + d.colorOffset(slot, 0), slot.width, slot.height, slot.kind);
  if (slot.views == 2) out.right = imageFrom(p + d.colorOffset(slot, 1), slot.width, slot.height, slot.kind);
  else if (slot.duplicate) out.right = out.left;
  if (slot.depth) {
    const std::vector<float> left = depthFrom(p + d.depthOffset(slot, 0), slot.width, slot.height);
    std::vector<float> right;
    if (slot.views == 2) right = depthFrom(p + d.depthOffset(slot, 1), slot.width, slot.height);
    auto image = [&](const std::vector<float>& px, const sequencer::CameraModel& cam) {
      return sequencer::DepthImage{slot.width, slot.height, px.data(), sequencer::DepthKind::ReversedZ, cam.nearClip,
                                   cam.farClip};
    };
    const sequencer::DepthImage l = image(left, slot.eyes.left);
    const sequencer::DepthImage r = image(right, slot.eyes.right);
    sequencer::FrameComfort fc{job.frame, sequencer::checkComfort(slot.eyes, l, right.empty() ? nullptr : &r,
                                                                  *d.options.comfort)};
    d.comfort.push_back(fc);
    if (onComfort) onComfort(fc);
  }
  slot.buffer.unmap();
  ++d.finished;
  return true;
}

}  // namespace hs::render
