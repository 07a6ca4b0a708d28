#include "sequencer/ffmpeg_writer.h"

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <pthread.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/srgb.h"
#include "core/subprocess.h"

namespace hs::sequencer {

namespace fs = std::filesystem;

std::optional<VideoContainer> videoContainerFromPath(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".mp4" || ext == ".mov") return VideoContainer::Mp4;
  if (ext == ".mkv") return VideoContainer::Mkv;
  return std::nullopt;
}

namespace {

// Starts `args` with stdin from `in` (or /dev/null) and stdout+stderr to `log`.
pid_t spawn(const std::vector<std::string>& args, int in, int log, std::string& error) {
  SpawnOptions o;
  o.args = args;
  o.searchPath = true;
  o.fds = {{0, in}, {1, log}, {2, log}};
  return spawnProcess(o, error, " (install it: apt-get install ffmpeg)");
}

// write() that reports a dead reader as EPIPE instead of killing the whole
// program with SIGPIPE: the signal is blocked on this thread while writing
// and a pending one is consumed.
bool writeAll(int fd, const uint8_t* data, size_t size, int& err) {
  sigset_t block, old;
  sigemptyset(&block);
  sigaddset(&block, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &block, &old);
  bool ok = true;
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      err = errno;
      ok = false;
      if (err == EPIPE) {
        const timespec zero{0, 0};
        sigtimedwait(&block, nullptr, &zero);
      }
      break;
    }
    data += n;
    size -= size_t(n);
  }
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  return ok;
}

const char* mkvStereoMode(StereoLayout l) {
  switch (l) {
    case StereoLayout::SideBySide:
    case StereoLayout::SideBySideSqueezed: return "left_right";
    case StereoLayout::TopBottom:
    case StereoLayout::TopBottomSqueezed: return "top_bottom";
    default: return nullptr;
  }
}

// x264's frame_packing_arrangement_type: 3 side by side, 4 top-bottom.
int x264FramePacking(StereoLayout l) {
  switch (l) {
    case StereoLayout::SideBySide:
    case StereoLayout::SideBySideSqueezed: return 3;
    case StereoLayout::TopBottom:
    case StereoLayout::TopBottomSqueezed: return 4;
    default: return -1;
  }
}

}  // namespace

bool ffmpegAvailable(const std::string& program) {
  std::string error;
  const int devnull = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (devnull < 0) return false;
  const pid_t pid = spawn({program, "-hide_banner", "-version"}, -1, devnull, error);
  ::close(devnull);
  return pid > 0 && waitProcess(pid) == 0;
}

std::vector<std::string> ffmpegEncodeArguments(const std::string& output, const VideoSettings& s) {
  std::vector<std::string> a = {s.ffmpeg, "-hide_banner", "-nostdin", "-loglevel", "error", "-y",
                                "-f", "rawvideo", "-pix_fmt", "rgba",
                                "-s", std::to_string(s.width) + "x" + std::to_string(s.height),
                                "-framerate", std::to_string(s.rate.num) + "/" + std::to_string(s.rate.den),
                                "-i", "pipe:0",
                                // sRGB frames to BT.709 video (what players assume for HD);
                                // without this swscale would use BT.601 and shift colours.
                                "-vf", "scale=out_color_matrix=bt709:out_range=tv",
                                "-pix_fmt", "yuv420p", "-color_primaries", "bt709", "-color_trc", "bt709",
                                "-colorspace", "bt709", "-color_range", "tv"};
  const int packing = x264FramePacking(s.layout);
  if (s.codec == VideoCodec::H264) {
    a.insert(a.end(), {"-c:v", "libx264", "-preset", s.preset, "-crf", std::to_string(s.crf)});
    if (packing >= 0) a.insert(a.end(), {"-x264-params", "frame-packing=" + std::to_string(packing)});
  } else {
    a.insert(a.end(), {"-c:v", "libx265", "-preset", s.preset, "-crf", std::to_string(s.crf),
                       "-tag:v", "hvc1", "-x265-params", "log-level=error"});
  }
  if (s.threads > 0) a.insert(a.end(), {"-threads", std::to_string(s.threads)});
  if (const char* mode = mkvStereoMode(s.layout)) a.insert(a.end(), {"-metadata:s:v:0", std::string("stereo_mode=") + mode});
  a.insert(a.end(), {"-f", "matroska", output});
  return a;
}

std::unique_ptr<VideoWriter> VideoWriter::open(const std::string& path, const VideoSettings& s, std::string& error) {
  const auto container = videoContainerFromPath(path);
  if (!container) {
    error = path + ": not a video file name; use .mp4 or .mkv";
    return nullptr;
  }
  const fs::path target(path);
  const fs::path dir = target.parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec)) {
    error = path + ": folder " + dir.string() + " does not exist";
    return nullptr;
  }
  if (s.width <= 0 || s.height <= 0 || s.width % 2 || s.height % 2) {
    error = path + ": video frames need an even width and height (4:2:0 chroma), not " + std::to_string(s.width) +
            "x" + std::to_string(s.height);
    return nullptr;
  }
  std::unique_ptr<VideoWriter> w(new VideoWriter());
  w->path_ = path;
  w->settings_ = s;
  const std::string stem = ".tmp-" + std::to_string(::getpid()) + "-" + target.filename().string();
  w->tempPath_ = (dir / (stem + ".mkv")).string();
  w->logPath_ = (dir / (stem + ".log")).string();
  const int log = ::open(w->logPath_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log < 0) {
    error = path + ": cannot write in " + (dir.empty() ? std::string(".") : dir.string()) + ": " + std::strerror(errno);
    return nullptr;
  }
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    ::close(log);
    error = path + ": cannot create a pipe: " + std::strerror(errno);
    return nullptr;
  }
  w->pid_ = spawn(ffmpegEncodeArguments(w->tempPath_, s), fds[0], log, error);
  ::close(fds[0]);
  ::close(log);
  if (w->pid_ < 0) {
    ::close(fds[1]);
    fs::remove(w->logPath_, ec);
    error = path + ": " + error;
    return nullptr;
  }
  w->pipe_ = fds[1];
  // Big frames: a larger pipe buffer lets ffmpeg read while we write.
  fcntl(w->pipe_, F_SETPIPE_SZ, 1 << 20);
  return w;
}

std::string VideoWriter::lastLog() const {
  std::ifstream in(logPath_);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  if (text.size() > 600) text = "..." + text.substr(text.size() - 600);
  return text;
}

bool VideoWriter::writeFrame(const Image& frame, std::string& error) {
  if (pipe_ < 0) {
    error = path_ + ": the video is closed";
    return false;
  }
  if (frame.width != settings_.width || frame.height != settings_.height) {
    error = path_ + ": frame is " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
            ", the video " + std::to_string(settings_.width) + "x" + std::to_string(settings_.height);
    return false;
  }
  const uint8_t* data = frame.rgba8.data();
  if (frame.isFloat()) {
    scratch_.resize(frame.pixelCount() * 4);
    for (size_t i = 0; i < frame.pixelCount(); ++i) {
      for (int c = 0; c < 3; ++c) scratch_[i * 4 + size_t(c)] = linearToSrgb8(frame.rgbaF[i * 4 + size_t(c)]);
      scratch_[i * 4 + 3] = 255;
    }
    data = scratch_.data();
  }
  int err = 0;
  if (!writeAll(pipe_, data, frame.pixelCount() * 4, err)) {
    // ffmpeg stopped reading: it failed (disk full, bad option); say what it said.
    ::close(pipe_);
    pipe_ = -1;
    const int code = waitProcess(pid_);
    pid_ = -1;
    const std::string log = lastLog();
    error = path_ + ": ffmpeg stopped at frame " + std::to_string(frames_) + " (exit " + std::to_string(code) +
            ", " + std::strerror(err) + ")" + (log.empty() ? "" : ": " + log);
    abort();
    return false;
  }
  ++frames_;
  return true;
}

bool VideoWriter::finishProcess(std::string& error) {
  if (pipe_ >= 0) ::close(pipe_);
  pipe_ = -1;
  if (pid_ < 0) return false;
  const int code = waitProcess(pid_);
  pid_ = -1;
  if (code != 0) {
    const std::string log = lastLog();
    error = path_ + ": ffmpeg failed (exit " + std::to_string(code) + ")" + (log.empty() ? "" : ": " + log);
    return false;
  }
  return true;
}

bool VideoWriter::close(std::string& error) {
  if (closed_) return true;
  if (!finishProcess(error)) {
    abort();
    return false;
  }
  std::error_code ec;
  std::string finished = tempPath_;
  if (videoContainerFromPath(path_) == VideoContainer::Mp4) {
    // MKV -> MP4 without re-encoding; -strict unofficial lets the MP4 muxer
    // write the stereo 'st3d' box from the MKV track's stereo mode.
    const fs::path target(path_);
    const std::string mp4 =
        (target.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" + target.filename().string())).string();
    const int log = ::open(logPath_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    std::vector<std::string> args = {settings_.ffmpeg, "-hide_banner", "-nostdin", "-loglevel", "error", "-y",
                                     "-i", tempPath_, "-c", "copy", "-movflags", "+faststart"};
    if (mkvStereoMode(settings_.layout)) args.insert(args.end(), {"-strict", "unofficial"});
    args.insert(args.end(), {"-f", "mp4", mp4});
    pid_ = spawn(args, -1, log < 0 ? 2 : log, error);
    if (log >= 0) ::close(log);
    if (pid_ < 0 || waitProcess(pid_) != 0) {
      pid_ = -1;
      error = path_ + ": remuxing to MP4 failed" + (lastLog().empty() ? "" : ": " + lastLog());
      fs::remove(mp4, ec);
      abort();
      return false;
    }
    pid_ = -1;
    fs::remove(tempPath_, ec);
    tempPath_ = mp4;
    finished = mp4;
  }
  fs::rename(finished, path_, ec);
  if (ec) {
    error = path_ + ": cannot move the finished video into place: " + ec.message();
    abort();
    return false;
  }
  fs::remove(logPath_, ec);
  closed_ = true;
  return true;
}

void VideoWriter::abort() {
  if (pipe_ >= 0) ::close(pipe_);
  pipe_ = -1;
  if (pid_ > 0) {
    ::kill(pid_, SIGTERM);
    waitProcess(pid_);
    pid_ = -1;
  }
  std::error_code ec;
  fs::remove(tempPath_, ec);
  fs::remove(logPath_, ec);
  closed_ = true;
}

VideoWriter::~VideoWriter() {
  if (!closed_) abort();
}

}  // namespace hs::sequencer
