#include "sequencer/export_loop.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "sequencer/frame_verify.h"
#include "sequencer/output_pattern.h"

namespace hs::sequencer {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

class CallbackSource final : public FrameSource {
 public:
  explicit CallbackSource(RenderFn fn) : fn_(std::move(fn)) {}
  bool begin(const FrameJob&, std::string&) override { return true; }
  bool finish(const FrameJob& job, EyeImages& out, std::string& error) override { return fn_(job, out, error); }

 private:
  RenderFn fn_;
};

struct WorkItem {
  FrameJob job;
  EyeImages eyes;
};

// A bounded FIFO: the renderer blocks when writers fall behind, so memory
// stays at queueDepth frames whatever the speed difference.
class BoundedQueue {
 public:
  explicit BoundedQueue(size_t capacity) : capacity_(capacity) {}
  // False if the queue was closed (the export is stopping).
  bool push(WorkItem item, double& waited) {
    std::unique_lock lock(m_);
    const auto t0 = Clock::now();
    notFull_.wait(lock, [&] { return items_.size() < capacity_ || closed_; });
    waited += secondsSince(t0);
    if (closed_) return false;
    items_.push_back(std::move(item));
    notEmpty_.notify_one();
    return true;
  }
  std::optional<WorkItem> pop() {
    std::unique_lock lock(m_);
    notEmpty_.wait(lock, [&] { return !items_.empty() || closed_; });
    if (items_.empty()) return std::nullopt;
    WorkItem item = std::move(items_.front());
    items_.pop_front();
    notFull_.notify_one();
    return item;
  }
  // No more pushes; pops drain what is left, then return nullopt.
  void close() {
    std::lock_guard lock(m_);
    closed_ = true;
    notEmpty_.notify_all();
    notFull_.notify_all();
  }

 private:
  std::mutex m_;
  std::condition_variable notEmpty_, notFull_;
  std::deque<WorkItem> items_;
  size_t capacity_;
  bool closed_ = false;
};

std::vector<std::pair<std::string, Eye>> outputsOf(const OutputPattern& p, StereoLayout layout, int64_t frame) {
  if (layoutFilesPerFrame(layout) == 2) return {{p.path(frame, Eye::Left), Eye::Left}, {p.path(frame, Eye::Right), Eye::Right}};
  return {{p.path(frame, Eye::Both), Eye::Both}};
}

}  // namespace

std::unique_ptr<FrameSource> makeCallbackSource(RenderFn render) {
  return std::make_unique<CallbackSource>(std::move(render));
}

ResumePlan planExport(const ExportSettings& s, bool dryRun) {
  ResumePlan plan;
  const std::vector<int64_t> frames = s.frames.frames();
  if (videoContainerFromPath(s.output)) {
    plan.toRender = frames;  // a film is written whole
    return plan;
  }
  std::string error;
  const auto pattern = OutputPattern::parse(s.output, error);
  if (!pattern) {
    plan.error = error;
    return plan;
  }
  if (!imageFormatFromPath(pattern->path(0))) {
    plan.error = s.output + ": unknown image type; use .png, .exr, .jpg, .tif, or .mp4 / .mkv for a film";
    return plan;
  }
  // Stray temporaries of our own frames: a killed run's half-written files.
  // Only names that belong to frames of this range go, so other exports
  // (farm chunks) sharing the folder are never touched.
  std::map<fs::path, std::set<std::string>> ours;
  for (int64_t f : frames)
    for (const auto& [path, eye] : outputsOf(*pattern, s.layout, f)) {
      const fs::path p(path);
      ours[p.parent_path()].insert(p.filename().string());
    }
  for (const auto& [dir, names] : ours) {
    std::error_code ec;
    // Output folders are made as needed (as Blender does); several farm
    // tasks doing it at once is fine. If it cannot be made, the first write
    // reports why, with the frame.
    if (!dryRun && !dir.empty()) fs::create_directories(dir, ec);
    const fs::path listDir = dir.empty() ? fs::path(".") : dir;
    for (fs::directory_iterator it(listDir, ec), end; !ec && it != end; it.increment(ec)) {
      std::string target;
      const std::string name = it->path().filename().string();
      if (!isTemporaryName(name, &target) || !names.count(target)) continue;
      ++plan.removedTemporaries;
      if (!dryRun) fs::remove(it->path(), ec);
    }
  }
  if (!s.resume) {
    plan.toRender = frames;
    return plan;
  }
  const glm::ivec2 size = layoutFrameSize(s.layout, s.eyeWidth, s.eyeHeight);
  for (int64_t f : frames) {
    bool valid = true, anyPresent = false;
    std::string why;
    for (const auto& [path, eye] : outputsOf(*pattern, s.layout, f)) {
      const FrameCheck c = checkFrameFile(path, size.x, size.y, s.jobTag);
      anyPresent = anyPresent || !c.missing;
      valid = valid && c.ok;
      if (!c.ok && !c.missing && why.empty()) why = c.problem;
    }
    if (valid) {
      ++plan.kept;
    } else {
      if (anyPresent) {
        ++plan.invalid;
        // A few reasons are enough to tell a changed scene (every frame "written
        // by another export") from damaged files; the count says the rest.
        if (plan.invalidWhy.size() < 5 && !why.empty()) plan.invalidWhy.push_back("frame " + std::to_string(f) + ": " + why);
      }
      plan.toRender.push_back(f);
    }
  }
  return plan;
}

ExportResult runExport(const ExportSettings& s, FrameSource& source, const ExportCallbacks& cb) {
  const auto t0 = Clock::now();
  ExportResult result;
  result.total = s.frames.count();
  const bool video = videoContainerFromPath(s.output).has_value();
  std::string error;
  std::optional<OutputPattern> pattern;
  if (!video) {
    pattern = OutputPattern::parse(s.output, error);
    if (!pattern) {
      result.error = error;
      return result;
    }
  }
  if (s.eyeWidth <= 0 || s.eyeHeight <= 0) {
    result.error = "eye size " + std::to_string(s.eyeWidth) + "x" + std::to_string(s.eyeHeight) + " is not an image size";
    return result;
  }
  if (video && s.layout == StereoLayout::Separate) {
    result.error = s.output + ": a film holds one picture a frame; choose sbs, tb or another single-image layout";
    return result;
  }
  const ResumePlan plan = planExport(s);
  if (!plan.error.empty()) {
    result.error = plan.error;
    return result;
  }
  result.kept = plan.kept;
  result.replaced = plan.invalid;
  result.removedTemporaries = plan.removedTemporaries;
  if (plan.removedTemporaries)
    result.notes.push_back("removed " + std::to_string(plan.removedTemporaries) +
                           " half-written temporary file(s) of an interrupted export");
  if (plan.kept) result.notes.push_back("kept " + std::to_string(plan.kept) + " valid frame(s) from an earlier run");
  if (plan.invalid) {
    std::string note = "rendering again " + std::to_string(plan.invalid) + " invalid frame(s) of an earlier run";
    for (const std::string& why : plan.invalidWhy) note += "\n  " + why;
    if (plan.invalid > int64_t(plan.invalidWhy.size()))
      note += "\n  ... and " + std::to_string(plan.invalid - int64_t(plan.invalidWhy.size())) + " more";
    result.notes.push_back(note);
  }

  const glm::ivec2 frameSize = layoutFrameSize(s.layout, s.eyeWidth, s.eyeHeight);
  std::unique_ptr<VideoWriter> film;
  if (video && !plan.toRender.empty()) {
    VideoSettings vs = s.video;
    vs.width = frameSize.x;
    vs.height = frameSize.y;
    vs.rate = s.rate;
    vs.layout = s.layout;
    film = VideoWriter::open(s.output, vs, error);
    if (!film) {
      result.error = error;
      return result;
    }
  }
  const bool wantFloat = !video && imageFormatFromPath(pattern->path(0)) == ImageFormat::Exr;
  WriteOptions writeOptions = s.image;
  if (!s.jobTag.empty()) writeOptions.description = frameDescription(s.jobTag);
  ImageSink sink = cb.sink;
  if (!sink)
    sink = [&writeOptions](const std::string& path, const Image& image, std::string& err) {
      return writeImage(path, image.view(), err, writeOptions);
    };

  // Shared state of the writers.
  std::mutex m;
  std::condition_variable turn;        // video: frames reach ffmpeg in order
  int64_t nextVideoIndex = 0;
  // After a write failure, queued frames after the failed one are dropped
  // (a full disk would fail them too) and frames before it still finish,
  // so "every frame before the reported one is on disk" holds whatever the
  // thread timing. A film is lost whole: everything is dropped.
  constexpr int64_t kRunning = std::numeric_limits<int64_t>::max();
  std::atomic<int64_t> stopAfter{kRunning};  // job index
  std::string firstError;
  std::optional<int64_t> failedFrame;
  std::atomic<int64_t> written{0};
  int64_t processed = 0;               // items taken off the queue (written, failed or dropped), under m
  int64_t pushed = 0;                  // items put on the queue (caller's thread)
  std::atomic<int64_t> lastFrame{-1};
  double writeSeconds = 0.0;
  std::deque<double> doneTimes;        // completion times for the ETA window

  // A write failure stops the writers too (the next frames would fail the
  // same way: a full disk); a render failure only stops rendering, and the
  // frames rendered before it are still written.
  auto fail = [&](const FrameJob& job, const std::string& why, bool stopWriters) {
    const int64_t frame = job.frame;
    std::lock_guard lock(m);
    // With several writers two frames can fail at once (a full disk): the
    // earliest frame is reported, so the message does not depend on timing.
    if (firstError.empty() || (failedFrame && frame < *failedFrame)) {
      firstError = "frame " + std::to_string(frame) + ": " + why;
      failedFrame = frame;
    }
    if (stopWriters) {
      const int64_t limit = film ? -1 : job.index;
      int64_t cur = stopAfter.load();
      while (limit < cur && !stopAfter.compare_exchange_weak(cur, limit)) {
      }
    }
    turn.notify_all();
  };

  const int threads = std::max(1, s.writerThreads);
  BoundedQueue queue(size_t(s.queueDepth > 0 ? s.queueDepth : threads + 1));
  // One frame on a writer thread: compose the layout, then write the file(s)
  // or hand the frame to ffmpeg in order. False with `err` on failure.
  enum class Outcome { Written, Skipped, Failed };
  auto processOne = [&](WorkItem& item, std::string& err) -> Outcome {
    const FrameJob& job = item.job;
    const int eyeW = item.eyes.left.width, eyeH = item.eyes.left.height;
    if (eyeW != s.eyeWidth || eyeH != s.eyeHeight) {
      err = "the renderer returned a " + std::to_string(eyeW) + "x" + std::to_string(eyeH) + " eye; expected " +
            std::to_string(s.eyeWidth) + "x" + std::to_string(s.eyeHeight);
      return Outcome::Failed;
    }
    std::vector<Image> images = composeLayout(s.layout, item.eyes.left, item.eyes.right, s.anaglyph);
    item.eyes = {};  // free the eyes early: memory stays at the queue's depth
    if (images.empty() || images.front().empty()) {
      err = "the renderer returned eye images of different sizes or pixel kinds";
      return Outcome::Failed;
    }
    if (film) {
      std::unique_lock lock(m);
      turn.wait(lock, [&] { return nextVideoIndex == job.index || stopAfter != kRunning; });
      if (stopAfter != kRunning) return Outcome::Skipped;  // another frame failed: the film is lost anyway
      lock.unlock();
      const bool ok = film->writeFrame(images.front(), err);
      lock.lock();
      ++nextVideoIndex;
      turn.notify_all();
      return ok ? Outcome::Written : Outcome::Failed;
    }
    const auto outs = outputsOf(*pattern, s.layout, job.frame);
    for (size_t i = 0; i < outs.size(); ++i)
      if (!sink(outs[i].first, images[i], err)) return Outcome::Failed;
    return Outcome::Written;
  };
  auto writer = [&] {
    while (auto item = queue.pop()) {
      if (item->job.index <= stopAfter) {  // after a failure, later frames drain without work
        const auto w0 = Clock::now();
        std::string err;
        const Outcome outcome = processOne(*item, err);
        if (outcome == Outcome::Failed) {
          fail(item->job, err, true);
        } else if (outcome == Outcome::Written) {  // a whole file, even if another frame failed meanwhile
          ++written;
          lastFrame = item->job.frame;
          std::lock_guard lock(m);
          writeSeconds += secondsSince(w0);
          doneTimes.push_back(secondsSince(t0));
          if (doneTimes.size() > 60) doneTimes.pop_front();
        }
      }
      std::lock_guard lock(m);
      ++processed;
      turn.notify_all();
    }
  };
  std::vector<std::thread> pool;
  for (int i = 0; i < threads; ++i) pool.emplace_back(writer);

  auto report = [&] {
    if (!cb.onFrame && !cb.progress) return;
    ExportProgress p;
    p.total = result.total;
    p.kept = result.kept;
    p.rendered = result.rendered;
    p.written = written;
    p.lastFrame = lastFrame;
    p.elapsedSeconds = secondsSince(t0);
    {
      std::lock_guard lock(m);
      if (doneTimes.size() >= 2) p.framesPerSecond = double(doneTimes.size() - 1) / (doneTimes.back() - doneTimes.front());
      else if (p.written > 0) p.framesPerSecond = double(p.written) / p.elapsedSeconds;
    }
    const int64_t remaining = int64_t(plan.toRender.size()) - p.written;
    if (p.framesPerSecond > 0.0) p.etaSeconds = double(remaining) / p.framesPerSecond;
    if (p.total > 0) reportProgress(cb.progress, double(p.kept + p.written) / double(p.total), "Rendering frames");
    if (cb.onFrame) cb.onFrame(p);
  };

  // The render loop, on the caller's thread.
  std::deque<FrameJob> inFlight;
  const size_t depth = size_t(std::max(1, source.framesInFlight()));
  double waitSeconds = 0.0;
  bool renderFailed = false;
  auto finishOldest = [&]() -> bool {
    FrameJob job = inFlight.front();
    inFlight.pop_front();
    WorkItem item{job, {}};
    const auto r0 = Clock::now();
    std::string err;
    const bool ok = source.finish(job, item.eyes, err);
    result.renderSeconds += secondsSince(r0);
    if (!ok) {
      fail(job, "render failed: " + err, false);
      renderFailed = true;
      return false;
    }
    ++result.rendered;
    if (stopAfter != kRunning) return false;
    if (queue.push(std::move(item), waitSeconds)) ++pushed;
    report();
    return true;
  };
  for (size_t i = 0; i < plan.toRender.size(); ++i) {
    if (stopAfter != kRunning || renderFailed || isCancelled(cb.progress)) break;
    FrameJob job;
    job.frame = plan.toRender[i];
    job.time = frameTime(job.frame, s.rate);
    job.index = int64_t(i);
    job.eyeWidth = s.eyeWidth;
    job.eyeHeight = s.eyeHeight;
    job.bothEyes = layoutRendersBothEyes(s.layout);
    job.floatPixels = wantFloat;
    const auto r0 = Clock::now();
    std::string err;
    const bool ok = source.begin(job, err);
    result.renderSeconds += secondsSince(r0);
    if (!ok) {
      fail(job, "render failed: " + err, false);
      renderFailed = true;
      break;
    }
    inFlight.push_back(job);
    if (inFlight.size() >= depth && !finishOldest()) break;
  }
  // Frames already begun are finished (the renderer's buffers stay
  // consistent) and, unless something failed, written: their work is done.
  while (!inFlight.empty() && !renderFailed) finishOldest();
  queue.close();
  // Progress while the writers drain the queue.
  while (true) {
    std::unique_lock lock(m);
    if (processed >= pushed) break;
    turn.wait_for(lock, std::chrono::milliseconds(100));
    lock.unlock();
    report();
  }
  for (auto& t : pool) t.join();

  result.written = written;
  result.writeSeconds = writeSeconds;
  result.waitSeconds = waitSeconds;
  if (film) {
    if (firstError.empty() && !isCancelled(cb.progress) && !film->close(error)) firstError = error;
    film.reset();  // an unfinished film is removed: it would not play to the end
  }
  result.cancelled = isCancelled(cb.progress) && firstError.empty();
  if (!firstError.empty()) {
    result.error = firstError;
    result.failedFrame = failedFrame;
    if (result.written > 0 || result.kept > 0)
      result.notes.push_back("the " + std::to_string(result.written + result.kept) +
                             " frame(s) finished before the failure are kept; run the export again to resume");
  }
  result.ok = firstError.empty() && !result.cancelled;
  result.seconds = secondsSince(t0);
  report();
  return result;
}

}  // namespace hs::sequencer
