// The camera-cut track (sequencer/camera_cuts.h): the shot of every frame
// against a brute-force reading of the rules (the cut covering the frame;
// during a transition the cut before until its first frame, both between,
// this cut's camera from its last frame on), the transitions' weights
// (crossfade sums to 1, a dip is black in the middle), the checks that
// name the cut (reversed, overlapping, a deleted camera, a transition on
// the first cut, after a gap, longer than its shots), and the JSON form.
#include <QtTest>

#include "sequencer/camera_cuts.h"
#include "sequencer/interpolation.h"
#include "sequencer/sequence_json.h"

using namespace hs::sequencer;

namespace {

std::string problemOf(const std::vector<CameraCut>& cuts) {
  return cutsProblem(
      cuts, [](uint64_t id) { return id == 1 || id == 2 || id == 3; },
      [](uint64_t id) { return "#" + std::to_string(id); });
}

CameraCut cut(uint64_t camera, int64_t start, int64_t end, Transition t = Transition::Cut, int64_t frames = 0,
              Ease ease = Ease::InOut) {
  return CameraCut{camera, start, end, t, frames, ease};
}

}  // namespace

class TestCameraCuts : public QObject {
  Q_OBJECT

 private slots:
  void everyFrameHasTheShotTheRulesSay() {
    const std::vector<CameraCut> cuts = {cut(1, 0, 99), cut(2, 100, 199, Transition::Crossfade, 20, Ease::None),
                                         cut(3, 250, 299), cut(1, 300, 400, Transition::DipToBlack, 40)};
    QCOMPARE(problemOf(cuts), std::string());
    for (int64_t f = -10; f <= 420; ++f) {
      const std::optional<Shot> s = shotAt(cuts, f);
      // Brute force: the cut whose range holds f.
      const CameraCut* holder = nullptr;
      for (const CameraCut& c : cuts)
        if (f >= c.start && f <= c.end) holder = &c;
      if (!holder) {
        QVERIFY2(!s, qPrintable(QString("frame %1 is in no cut").arg(f)));
        continue;
      }
      QVERIFY(s);
      const int64_t into = f - holder->start;
      if (holder->transition == Transition::Cut || into >= holder->transitionFrames) {
        QCOMPARE(s->camera, holder->camera);
        QCOMPARE(s->incoming, uint64_t(0));
        continue;
      }
      const CameraCut& before = *(holder - 1);
      QCOMPARE(s->camera, before.camera);
      if (into == 0) {  // the transition's first frame: the shot before alone
        QCOMPARE(s->incoming, uint64_t(0));
        continue;
      }
      QCOMPARE(s->incoming, holder->camera);
      QCOMPARE(s->transition, holder->transition);
      QCOMPARE(s->progress, easeValue(holder->ease, double(into) / double(holder->transitionFrames)));
    }
    // Exactly: the transition's last frame is the incoming camera alone.
    QCOMPARE(shotAt(cuts, 120)->camera, uint64_t(2));
    QCOMPARE(shotAt(cuts, 120)->incoming, uint64_t(0));
    QCOMPARE(shotAt(cuts, 100)->camera, uint64_t(1));
    QCOMPARE(shotAt(cuts, 100)->incoming, uint64_t(0));
  }

  void weights() {
    Shot s{1, 2, Transition::Crossfade, 0.25};
    QCOMPARE(s.weights(), (std::pair<float, float>{0.75f, 0.25f}));
    s.transition = Transition::DipToBlack;
    QCOMPARE(s.weights(), (std::pair<float, float>{0.5f, 0.0f}));
    s.progress = 0.5;
    QCOMPARE(s.weights(), (std::pair<float, float>{0.0f, 0.0f}));  // black in the middle
    s.progress = 0.75;
    QCOMPARE(s.weights(), (std::pair<float, float>{0.0f, 0.5f}));
    s.incoming = 0;
    QCOMPARE(s.weights(), (std::pair<float, float>{1.0f, 0.0f}));
  }

  void unsoundTracksAreNamed() {
    struct Case {
      std::vector<CameraCut> cuts;
      const char* says;
    } cases[] = {
        {{cut(1, 50, 10)}, "cut 1 (frames 50-10): its end is before its start"},
        {{cut(1, 0, 100), cut(2, 100, 200)}, "cut 2 (frames 100-200): it overlaps cut 1 (frames 0-100)"},
        {{cut(1, 0, 100), cut(7, 101, 200)}, "cut 2 (frames 101-200): camera #7 is not a camera of the scene"},
        {{cut(1, 0, 100, Transition::Crossfade, 10)}, "cut 1 (frames 0-100): the first cut has no shot before it"},
        {{cut(1, 0, 100), cut(2, 110, 200, Transition::Crossfade, 10)},
         "cut 2 (frames 110-200): its crossfade needs cut 1 to end on frame 109 (it ends on 100)"},
        {{cut(1, 0, 100), cut(2, 101, 120, Transition::DipToBlack, 30)},
         "cut 2 (frames 101-120): its dip_to_black of 30 frames is longer than this shot (19 frames after its first)"},
        {{cut(1, 0, 5), cut(2, 6, 120, Transition::Crossfade, 30)},
         "cut 2 (frames 6-120): its crossfade of 30 frames is longer than the shot before (5 frames after its first)"},
        {{cut(1, 0, 100), cut(2, 101, 200, Transition::Crossfade, 0)}, "needs a length of at least 1 frame"},
        {{cut(1, 0, 100), cut(2, 101, 200, Transition::Cut, 5)}, "a plain cut has no transition length"},
    };
    for (const Case& c : cases) {
      const std::string p = problemOf(c.cuts);
      QVERIFY2(p.find(c.says) != std::string::npos, p.c_str());
    }
  }

  void jsonRoundTrip() {
    Sequence s;
    s.cuts = {cut(1, 0, 99), cut(2, 100, 199, Transition::DipToBlack, 24, Ease::Out)};
    const std::string text = sequenceToJsonText(s);
    QVERIFY(text.find("\"version\":3") != std::string::npos || text.find("\"version\": 3") != std::string::npos);
    std::string error;
    const std::optional<Sequence> back = sequenceFromJsonText(text, error);
    QVERIFY2(back, error.c_str());
    QVERIFY(back->cuts == s.cuts);
    // Without cuts the version stays what older builds read.
    QVERIFY(sequenceToJsonText(Sequence{}).find("\"version\": 3") == std::string::npos);
    // A bad member is named by its place.
    const std::string bad = R"({"format": "hybridscape-sequence", "version": 3, "rate": [60, 1], "start": 0, "end": 9,
 "bindings": [], "cuts": [{"camera": 1, "start": 0, "end": 9, "transition": "swirl", "frames": 3}]})";
    QVERIFY(!sequenceFromJsonText(bad, error));
    QVERIFY2(error.find("cuts[0].transition") == 0 && error.find("unknown transition 'swirl'") != std::string::npos,
             error.c_str());
  }
};

QTEST_GUILESS_MAIN(TestCameraCuts)
#include "test_camera_cuts.moc"
