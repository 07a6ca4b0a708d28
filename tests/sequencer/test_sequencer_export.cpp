// Frame export: complete and valid sequences, resume after a simulated kill
// (byte-identical to an uninterrupted run; the real SIGKILL of a real
// hybridscape-cli is in tests/cli/test_cli_sequence.cpp), split runs,
// job tags, unwritable folders and full disks (clear errors with the frame
// number, finished frames kept), formats, layouts, progress, verification,
// and direct video with stereo metadata checked by ffprobe.
#include <QtTest>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sys/mount.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "sequencer/export_loop.h"
#include "sequencer/frame_verify.h"
#include "sequencer/output_pattern.h"
#include "synthetic_frames.h"
#include "truncation.h"

using namespace hs::sequencer;
using hs::Image;
using hs::ImageView;
namespace fs = std::filesystem;

namespace {

constexpr int kEyeW = 96, kEyeH = 54;

ExportSettings settingsFor(const std::string& dir, const std::string& frames, const std::string& name = "f_%05d.png") {
  ExportSettings s;
  std::string error;
  s.frames = *FrameList::parse(frames, error);
  s.output = dir + "/" + name;
  s.eyeWidth = kEyeW;
  s.eyeHeight = kEyeH;
  return s;
}

ExportResult run(const ExportSettings& s, const ExportCallbacks& cb = {}) {
  auto source = makeCallbackSource(hs::test::syntheticRender);
  return runExport(s, *source, cb);
}

std::string readAll(const fs::path& p) {
  QFile f(QString::fromStdString(p.string()));
  if (!f.open(QIODevice::ReadOnly)) return {};
  return f.readAll().toStdString();
}

int countTemporaries(const std::string& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (isTemporaryName(e.path().filename().string())) ++n;
  return n;
}

// Every file of `frames` in both folders has the same bytes.
bool sameFrames(const std::string& a, const std::string& b, int64_t first, int64_t last, std::string& why) {
  for (int64_t f = first; f <= last; ++f) {
    char name[32];
    std::snprintf(name, sizeof name, "f_%05lld.png", static_cast<long long>(f));
    const std::string x = readAll(fs::path(a) / name), y = readAll(fs::path(b) / name);
    if (x.empty() || x != y) {
      why = std::string(name) + (x.empty() ? " is missing in the reference" : " differs");
      return false;
    }
  }
  return true;
}

// A tmpfs mounted for the test (root only); unmounted when it goes.
struct TmpfsMount {
  std::string dir;
  bool mounted = false;
  TmpfsMount(const std::string& d, const char* options) : dir(d) {
    fs::create_directories(dir);
    mounted = ::geteuid() == 0 && ::mount("tmpfs", dir.c_str(), "tmpfs", 0, options) == 0;
  }
  ~TmpfsMount() {
    if (mounted) ::umount(dir.c_str());
  }
};

// A frame source with two frames in flight, recording its calls.
class PipelinedSource : public FrameSource {
 public:
  std::vector<std::string> calls;
  bool begin(const FrameJob& job, std::string&) override {
    calls.push_back("b" + std::to_string(job.frame));
    return true;
  }
  bool finish(const FrameJob& job, EyeImages& out, std::string& err) override {
    calls.push_back("f" + std::to_string(job.frame));
    return hs::test::syntheticRender(job, out, err);
  }
  int framesInFlight() const override { return 2; }
};

}  // namespace

class TestExport : public QObject {
  Q_OBJECT

  QTemporaryDir tmp_;
  std::string reference_;  // an uninterrupted run of frames 0-29

  std::string dir(const char* name) {
    const std::string d = tmp_.path().toStdString() + "/" + name;
    fs::create_directories(d);
    return d;
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    reference_ = dir("reference");
    const ExportResult r = run(settingsFor(reference_, "0-29"));
    QVERIFY2(r.ok, r.error.c_str());
    QCOMPARE(r.rendered, int64_t(30));
    QCOMPARE(r.written, int64_t(30));
  }

  void uninterruptedRunIsCompleteAndValid() {
    VerifySettings v;
    v.frames = FrameList::range(0, 29);
    v.outputPattern = reference_ + "/f_%05d.png";
    v.eyeWidth = kEyeW;
    v.eyeHeight = kEyeH;
    v.deep = true;
    const VerifyReport rep = verifyFrames(v);
    QVERIFY2(rep.complete(), rep.summary().c_str());
    QCOMPARE(countTemporaries(reference_), 0);
    // A second run keeps everything and renders nothing.
    const ExportResult again = run(settingsFor(reference_, "0-29"));
    QVERIFY(again.ok);
    QCOMPARE(again.kept, int64_t(30));
    QCOMPARE(again.rendered, int64_t(0));
  }

  void resumeAfterSimulatedKill() {
    const std::string d = dir("resume");
    ExportSettings s = settingsFor(d, "0-29");
    hs::Progress cancel;
    auto source = makeCallbackSource([&](const FrameJob& job, EyeImages& out, std::string& err) {
      if (job.frame == 12) cancel.cancel();  // stop mid-run
      return hs::test::syntheticRender(job, out, err);
    });
    ExportCallbacks cb;
    cb.progress = &cancel;
    const ExportResult first = runExport(s, *source, cb);
    QVERIFY(first.cancelled && !first.ok);
    QCOMPARE(first.written, int64_t(13));  // frames already rendered are written
    // What a kill leaves: a half-written temporary of the next frame; and,
    // for good measure, a damaged file and a wrong-sized image.
    const std::string whole = readAll(fs::path(reference_) / "f_00013.png");
    std::ofstream(fs::path(d) / ".tmp-99999-f_00013.png", std::ios::binary) << whole.substr(0, whole.size() / 2);
    std::ofstream(fs::path(d) / "f_00014.png", std::ios::binary) << "not an image";
    std::ofstream(fs::path(d) / ".tmp-99999-f_99999.png", std::ios::binary) << "someone else's";
    {
      ExportSettings other = settingsFor(d, "15");
      other.eyeWidth = 10;
      QVERIFY(run(other).ok);
    }
    const ExportResult resumed = run(s);
    QVERIFY2(resumed.ok, resumed.error.c_str());
    QCOMPARE(resumed.kept, int64_t(13));
    QCOMPARE(resumed.replaced, int64_t(2));
    QCOMPARE(resumed.removedTemporaries, int64_t(1));
    QCOMPARE(resumed.rendered, int64_t(17));
    std::string why;
    QVERIFY2(sameFrames(reference_, d, 0, 29, why), why.c_str());
    QVERIFY(fs::exists(fs::path(d) / ".tmp-99999-f_99999.png"));  // not ours: left alone
    fs::remove(fs::path(d) / ".tmp-99999-f_99999.png");
    QCOMPARE(countTemporaries(d), 0);
  }

  // A real export process killed with SIGKILL and resumed is tested with the
  // real CLI and renderer: tests/cli/test_cli_sequence.cpp, killedMidFrameThenResumed.

  void splitRunsAreByteIdentical() {
    const std::string d = dir("split");
    ExportSettings a = settingsFor(d, "15-29");
    a.writerThreads = 1;
    ExportSettings b = settingsFor(d, "0-14");
    b.writerThreads = 3;
    QVERIFY(run(a).ok);
    QVERIFY(run(b).ok);
    std::string why;
    QVERIFY2(sameFrames(reference_, d, 0, 29, why), why.c_str());
    // A pipelined source (two frames in flight) writes the same frames.
    const std::string e = dir("pipelined");
    PipelinedSource src;
    const ExportResult r = runExport(settingsFor(e, "0-29"), src);
    QVERIFY(r.ok);
    QVERIFY2(sameFrames(reference_, e, 0, 29, why), why.c_str());
    QCOMPARE(src.calls[0], std::string("b0"));
    QCOMPARE(src.calls[1], std::string("b1"));  // frame 1 begins before frame 0 is read back
    QCOMPARE(src.calls[2], std::string("f0"));
  }

  void jobTagDecidesWhatResumeKeeps() {
    const std::string d = dir("tagged");
    ExportSettings s = settingsFor(d, "0-4");
    s.jobTag = "scene-hash-a";
    QVERIFY(run(s).ok);
    QCOMPARE(run(s).kept, int64_t(5));
    s.jobTag = "scene-hash-b";  // the scene changed: nothing is kept
    const ExportResult r = run(s);
    QCOMPARE(r.kept, int64_t(0));
    QCOMPARE(r.replaced, int64_t(5));
    const FrameCheck c = checkFrameFile(d + "/f_00000.png", 2 * kEyeW, kEyeH, "scene-hash-a");
    QVERIFY(!c.ok && c.problem.find("another export") != std::string::npos);
  }

  void unwritableFolderNamesTheFrame() {
    const std::string d = tmp_.path().toStdString() + "/readonly";
    std::unique_ptr<TmpfsMount> mount;
    if (::geteuid() == 0) {
      mount = std::make_unique<TmpfsMount>(d, "ro,size=64k");
      if (!mount->mounted) QSKIP("running as root without permission to mount a read-only tmpfs");
    } else {
      fs::create_directories(d);
      fs::permissions(d, fs::perms::owner_read | fs::perms::owner_exec);
    }
    const ExportResult r = run(settingsFor(d, "0-9"));
    if (::geteuid() != 0) fs::permissions(d, fs::perms::owner_all);
    QVERIFY(!r.ok);
    qInfo("%s", r.error.c_str());
    QVERIFY(r.failedFrame.has_value() && *r.failedFrame == 0);
    QVERIFY(r.error.rfind("frame 0: ", 0) == 0);
    QVERIFY(r.error.find("f_00000.png") != std::string::npos);
    QVERIFY(r.error.find("read-only") != std::string::npos || r.error.find("not writable") != std::string::npos);
  }

  void fullDiskKeepsWhatWasWritten() {
    if (::geteuid() != 0) QSKIP("needs root to mount a small tmpfs; failingWriter covers the logic");
    const std::string d = tmp_.path().toStdString() + "/full";
    TmpfsMount mount(d, "size=64k");
    if (!mount.mounted) QSKIP("cannot mount a tmpfs here");
    ExportSettings s = settingsFor(d, "0-99");
    s.writerThreads = 2;
    const ExportResult r = run(s);
    QVERIFY(!r.ok);
    qInfo("%s", r.error.c_str());
    QVERIFY(r.failedFrame.has_value());
    QVERIFY(r.error.rfind("frame " + std::to_string(*r.failedFrame) + ": ", 0) == 0);
    QVERIFY(r.error.find("disk full") != std::string::npos);
    QVERIFY(r.written > 0);
    // What was written is there, whole; no temporary is left.
    int valid = 0;
    for (const auto& e : fs::directory_iterator(d)) {
      QVERIFY2(!isTemporaryName(e.path().filename().string()), "a temporary file was left behind");
      const FrameCheck c = checkFrameFile(e.path().string(), 2 * kEyeW, kEyeH, {}, true);
      QVERIFY2(c.ok, c.problem.c_str());
      ++valid;
    }
    QCOMPARE(int64_t(valid), r.written);
    QVERIFY(!fs::exists(fs::path(d) / ("f_" + QString::number(*r.failedFrame).rightJustified(5, '0').toStdString() + ".png")));
    QVERIFY(!r.notes.empty());
  }

  // A frame cut short (a copy that stopped, a full disk on the farm's file
  // server) in every format the export writes: the check refuses it naming
  // the file, unless the cut lost only bytes the pixels do not need (then
  // they decode to the same pixels as the whole file). The default check
  // (what resume and `farm verify` run) refuses every cut by structure
  // alone: PNG chunks and CRCs up to IEND, the JPEG EOI marker, EXR chunks
  // and TIFF strips within the file.
  void framesCutShortFailTheCheck_data() {
    QTest::addColumn<QString>("name");
    QTest::addColumn<bool>("deep");
    for (bool deep : {true, false})
      for (const char* n : {"c_%05d.png", "c_%05d.jpg", "c_%05d.exr", "c_%05d.tif"})
        QTest::newRow((std::string(n) + (deep ? " deep" : " default")).c_str()) << QString(n) << deep;
  }
  void framesCutShortFailTheCheck() {
    QFETCH(QString, name);
    QFETCH(bool, deep);
    const std::string d = dir("cut");
    QVERIFY(run(settingsFor(d, "0", name.toStdString())).ok);
    const std::string ext = name.toStdString().substr(name.toStdString().rfind('.'));
    const std::string frame = d + "/c_00000" + ext;
    const std::string bytes = readAll(frame);
    QVERIFY(!bytes.empty());
    auto pixels = [](const std::string& file) {
      std::vector<float> px;
      auto in = OIIO::ImageInput::open(file);
      if (!in) return px;
      px.resize(size_t(in->spec().image_pixels()) * size_t(in->spec().nchannels));
      if (!in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::FLOAT, px.data())) px.clear();
      return px;
    };
    const std::vector<float> whole = pixels(frame);
    QVERIFY(!whole.empty());
    const std::string cut = d + "/cut" + ext;
    size_t passed = 0;
    size_t refused = 0;
    for (size_t n : hs::test::cutLengths(bytes.size(), bytes.size() / 40 + 1)) {
      std::ofstream(cut, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(n));
      const FrameCheck c = checkFrameFile(cut, 2 * kEyeW, kEyeH, {}, deep);
      const QByteArray where = QByteArray("cut at byte ") + QByteArray::number(qulonglong(n)) + " of " +
                               QByteArray::number(qulonglong(bytes.size())) + ": ";
      if (c.ok) {
        ++passed;
        QVERIFY2(pixels(cut) == whole, where + "passed the deep check with other pixels");
        continue;
      }
      QVERIFY2(c.problem.find(cut) != std::string::npos, where + c.problem.c_str());
      ++refused;
    }
    QVERIFY(refused > 0);
    if (passed) qInfo("%zu cut(s) passed with the whole file's pixels", passed);
    // The default check (structure) refuses every cut of a file the export
    // wrote, in each format: nothing after the data it checks.
    if (!deep) QCOMPARE(passed, size_t(0));
  }

  // Issue 10: a frame cut to half its size before a resumed export was kept
  // among the valid frames. Now resume renders it again, says which and why,
  // and the result equals an uninterrupted run; verify (default, not deep)
  // names it first.
  void frameCutInHalfIsRenderedAgainOnResume_data() {
    QTest::addColumn<QString>("ext");
    for (const char* e : {"png", "jpg", "exr", "tif"}) QTest::newRow(e) << QString(e);
  }
  void frameCutInHalfIsRenderedAgainOnResume() {
    QFETCH(QString, ext);
    const std::string d = dir(("half-" + ext).toStdString().c_str());
    const std::string name = "h_%05d." + ext.toStdString();
    QVERIFY(run(settingsFor(d, "0-4", name)).ok);
    const std::string frame = d + "/h_00002." + ext.toStdString();
    const std::string whole = readAll(frame);
    QVERIFY(whole.size() > 100);
    fs::resize_file(frame, whole.size() / 2);

    VerifySettings v;
    v.frames = FrameList::range(0, 4);
    v.outputPattern = d + "/" + name;
    v.eyeWidth = kEyeW;
    v.eyeHeight = kEyeH;
    const VerifyReport rep = verifyFrames(v);
    QCOMPARE(rep.validFrames, int64_t(4));
    QCOMPARE(int(rep.invalid.size()), 1);
    QCOMPARE(rep.invalid[0].first, int64_t(2));
    QVERIFY2(rep.invalid[0].second.find(frame) != std::string::npos, rep.invalid[0].second.c_str());
    QVERIFY2(rep.summary().find("invalid frame 2: ") != std::string::npos, rep.summary().c_str());

    const ExportResult r = run(settingsFor(d, "0-4", name));
    QVERIFY2(r.ok, r.error.c_str());
    QCOMPARE(r.kept, int64_t(4));
    QCOMPARE(r.replaced, int64_t(1));
    QCOMPARE(r.written, int64_t(1));
    std::string notes;
    for (const std::string& n : r.notes) notes += n + "\n";
    QVERIFY2(notes.find("rendering again 1 invalid frame(s)") != std::string::npos, notes.c_str());
    QVERIFY2(notes.find("frame 2: " + frame + ": damaged") != std::string::npos, notes.c_str());
    QVERIFY2(readAll(frame) == whole, "the frame rendered again differs from the first run's");
    QVERIFY(verifyFrames(v).complete());
  }

  void failingWriterStopsWithTheFrameNumber() {
    for (int threads : {1, 2}) {
      const std::string d = dir(threads == 1 ? "failing1" : "failing2");
      ExportSettings s = settingsFor(d, "0-19");
      s.writerThreads = threads;
      ExportCallbacks cb;
      cb.sink = [](const std::string& path, const Image& image, std::string& err) {
        if (path.find("f_00005") != std::string::npos) {
          err = path + ": cannot write: disk full in test (simulated)";
          return false;
        }
        return writeImage(path, image.view(), err);
      };
      const ExportResult r = run(s, cb);
      QVERIFY(!r.ok);
      QCOMPARE(*r.failedFrame, int64_t(5));
      QVERIFY2(r.error.rfind("frame 5: ", 0) == 0, r.error.c_str());
      for (int f = 0; f < 5; ++f) QVERIFY(checkFrameFile(d + "/f_0000" + std::to_string(f) + ".png", 2 * kEyeW, kEyeH).ok);
      QVERIFY(!fs::exists(d + "/f_00005.png"));
      QVERIFY(r.written >= 5 && r.written < 20);
    }
  }

  void renderFailureStops() {
    const std::string d = dir("renderfail");
    auto source = makeCallbackSource([](const FrameJob& job, EyeImages& out, std::string& err) {
      if (job.frame == 3) {
        err = "GPU lost";
        return false;
      }
      return hs::test::syntheticRender(job, out, err);
    });
    const ExportResult r = runExport(settingsFor(d, "0-9"), *source);
    QVERIFY(!r.ok);
    QCOMPARE(r.error, std::string("frame 3: render failed: GPU lost"));
    QVERIFY(fs::exists(d + "/f_00002.png"));
    // Eyes of the wrong size are refused, not written.
    auto wrong = makeCallbackSource([](const FrameJob& job, EyeImages& out, std::string& err) {
      FrameJob j = job;
      j.eyeWidth = 10;
      return hs::test::syntheticRender(j, out, err);
    });
    const ExportResult w = runExport(settingsFor(dir("wrongsize"), "0-3"), *wrong);
    QVERIFY(!w.ok && w.error.find("expected 96x54") != std::string::npos);
  }

  void formatsAndLayouts() {
    const std::string d = dir("formats");
    for (const char* name : {"f_%05d.exr", "f_%05d.jpg", "f_%05d.tif", "p16_%05d.png"}) {
      ExportSettings s = settingsFor(d, "0-1", name);
      s.image.png16 = std::string(name).rfind("p16", 0) == 0;
      s.jobTag = "job-42";
      const ExportResult r = run(s);
      QVERIFY2(r.ok, r.error.c_str());
      // Every format carries the job tag, so resume can trust it.
      const ExportResult again = run(s);
      QVERIFY2(again.kept == 2, name);
      std::string error;
      auto in = OIIO::ImageInput::open(OutputPattern::parse(s.output, error)->path(1));
      QVERIFY(in);
      QCOMPARE(in->spec().width, 2 * kEyeW);
      if (std::string(name).find("exr") != std::string::npos) QCOMPARE(in->spec().format, OIIO::TypeDesc(OIIO::TypeDesc::HALF));
      if (s.image.png16) QCOMPARE(in->spec().format, OIIO::TypeDesc(OIIO::TypeDesc::UINT16));
    }
    // Separate eyes: two files a frame; mono: one eye rendered.
    ExportSettings sep = settingsFor(d, "0-2", "s_%05d.png");
    sep.layout = StereoLayout::Separate;
    QVERIFY(run(sep).ok);
    QVERIFY(checkFrameFile(d + "/s_00002_left.png", kEyeW, kEyeH).ok);
    QVERIFY(checkFrameFile(d + "/s_00002_right.png", kEyeW, kEyeH).ok);
    QVERIFY(readAll(d + "/s_00002_left.png") != readAll(d + "/s_00002_right.png"));
    ExportSettings mono = settingsFor(d, "0-2", "m_%05d.png");
    mono.layout = StereoLayout::Mono;
    bool sawBoth = false;
    auto monoSource = makeCallbackSource([&](const FrameJob& job, EyeImages& out, std::string& err) {
      sawBoth = sawBoth || job.bothEyes;
      return hs::test::syntheticRender(job, out, err);
    });
    QVERIFY(runExport(mono, *monoSource).ok);
    QVERIFY(!sawBoth);
    QVERIFY(checkFrameFile(d + "/m_00001.png", kEyeW, kEyeH).ok);
    ExportSettings ana = settingsFor(d, "0", "a_%05d.jpg");
    ana.layout = StereoLayout::Anaglyph;
    QVERIFY(run(ana).ok);
    QVERIFY(checkFrameFile(d + "/a_00000.jpg", kEyeW, kEyeH).ok);
    // Missing output folders are made.
    QVERIFY(run(settingsFor(d, "0", "new/nested/n_%05d.png")).ok);
    QVERIFY(checkFrameFile(d + "/new/nested/n_00000.png", 2 * kEyeW, kEyeH).ok);
    // Bad patterns and names are refused up front.
    QVERIFY(run(settingsFor(d, "0", "nonumber.png")).error.find("no frame number") != std::string::npos);
    QVERIFY(run(settingsFor(d, "0", "f_%05d.bmp")).error.find("unknown image type") != std::string::npos);
  }

  void progressWithEta() {
    const std::string d = dir("progress");
    std::vector<ExportProgress> seen;
    ExportCallbacks cb;
    cb.onFrame = [&](const ExportProgress& p) { seen.push_back(p); };
    const ExportResult r = run(settingsFor(d, "0-19"), cb);
    QVERIFY(r.ok);
    QVERIFY(seen.size() >= 20);
    QCOMPARE(seen.back().written, int64_t(20));
    QCOMPARE(seen.back().total, int64_t(20));
    QCOMPARE(seen.back().etaSeconds, 0.0);
    bool etaSeen = false;
    for (const auto& p : seen) etaSeen = etaSeen || (p.etaSeconds > 0.0 && p.written < 20);
    QVERIFY(etaSeen);
    QVERIFY(r.renderSeconds > 0.0 && r.writeSeconds > 0.0);
  }

  void verifyReportsMissingAndInvalidFrames() {
    const std::string d = dir("verify");
    QVERIFY(run(settingsFor(d, "0-29")).ok);
    fs::remove(d + "/f_00003.png");
    std::ofstream(d + "/f_00017.png", std::ios::binary) << "junk";
    VerifySettings v;
    v.frames = FrameList::range(0, 29);
    v.outputPattern = d + "/f_%05d.png";
    v.eyeWidth = kEyeW;
    v.eyeHeight = kEyeH;
    v.chunkSize = 10;
    const VerifyReport rep = verifyFrames(v);
    QVERIFY(!rep.complete());
    QCOMPARE(rep.validFrames, int64_t(28));
    QCOMPARE(rep.missing, (std::vector<int64_t>{3}));
    QCOMPARE(rep.invalid.size(), size_t(1));
    QCOMPARE(rep.invalid[0].first, int64_t(17));
    QCOMPARE(rep.chunksToRerun, (std::vector<int64_t>{0, 1}));
    const std::string text = rep.summary();
    qInfo("%s", text.c_str());
    QVERIFY(text.find("missing frames: 3") != std::string::npos);
    QVERIFY(text.find("chunks (job-array tasks) to run again: 0-1") != std::string::npos);
  }

  void videoWithStereoMetadata() {
    if (!ffmpegAvailable()) QSKIP("ffmpeg is not installed (apt-get install ffmpeg)");
    const std::string d = dir("video");
    struct Case {
      const char* name;
      VideoCodec codec;
      StereoLayout layout;
      const char* expect;
    } cases[] = {{"film.mp4", VideoCodec::H264, StereoLayout::SideBySide, "side by side"},
                 {"film.mkv", VideoCodec::H265, StereoLayout::SideBySide, "side by side"},
                 {"film_h265.mp4", VideoCodec::H265, StereoLayout::SideBySide, "side by side"},
                 {"film_tb.mkv", VideoCodec::H264, StereoLayout::TopBottom, "top and bottom"}};
    for (const Case& c : cases) {
      ExportSettings s = settingsFor(d, "0-29", c.name);
      s.layout = c.layout;
      s.video.codec = c.codec;
      s.video.preset = "ultrafast";
      const ExportResult r = run(s);
      QVERIFY2(r.ok, r.error.c_str());
      QCOMPARE(r.written, int64_t(30));
      auto probe = [&](const QStringList& args) {
        QProcess p;
        p.start("ffprobe", QStringList{"-v", "error", "-of", "json"} + args + QStringList{QString::fromStdString(d + "/" + c.name)});
        p.waitForFinished(30000);
        return p.readAllStandardOutput();
      };
      const QByteArray streams = probe({"-count_frames", "-show_streams"});
      QVERIFY2(streams.contains("\"nb_read_frames\": \"30\""), streams.constData());
      // The container's flag (MKV StereoMode, MP4 st3d) shows as stream side data.
      QVERIFY2(streams.contains("Stereo 3D") && streams.contains(c.expect), streams.constData());
      if (c.codec == VideoCodec::H264) {
        // H.264 also carries the frame-packing SEI in every frame.
        const QByteArray frames = probe({"-show_frames", "-read_intervals", "%+#1", "-show_entries", "frame=side_data_list"});
        QVERIFY2(frames.contains("Stereo 3D"), frames.constData());
      }
      qInfo("%s (%s): ffprobe sees 'Stereo 3D: %s'", c.name, c.codec == VideoCodec::H264 ? "H.264" : "H.265", c.expect);
    }
    QCOMPARE(countTemporaries(d), 0);
    // ffmpeg's own failure comes back in words.
    ExportSettings bad = settingsFor(d, "0-5", "bad.mp4");
    bad.video.preset = "no-such-preset";
    const ExportResult r = run(bad);
    QVERIFY(!r.ok);
    qInfo("%s", r.error.c_str());
    QVERIFY(r.error.find("ffmpeg") != std::string::npos);
    QVERIFY(!fs::exists(d + "/bad.mp4"));
    QCOMPARE(countTemporaries(d), 0);
  }
};

QTEST_APPLESS_MAIN(TestExport)
#include "test_sequencer_export.moc"
