// core/image_io: the door to image files, with OpenImageIO in a module
// loaded on first use. Checked here:
// - laziness: no OpenImageIO library is mapped until the first image call,
//   and the programs (CLI, editor, import worker) do not link it at all;
// - a missing module is an error naming where it was looked for;
// - round trips against an independent codec (Qt's PNG reader and writer)
//   and the values themselves (straight alpha both ways): 8- and 16-bit
//   PNG, float EXR with channel
//   names and text metadata, TIFF, JPEG within its loss;
// - bad input: a missing file, bytes that are no image, a PNG cut short,
//   an unknown extension, a folder that does not exist.
#include <QBuffer>
#include <QImage>
#include <QTemporaryDir>
#include <QtTest>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "core/image_io.h"
#include "loaded_libraries.h"

using namespace hs;
namespace io = hs::image_io;

namespace {

bool openImageIoMapped() { return test::mappedHere("libOpenImageIO"); }

std::vector<uint8_t> gradientRgba(int w, int h) {
  std::vector<uint8_t> p(size_t(w) * size_t(h) * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* q = &p[(size_t(y) * size_t(w) + size_t(x)) * 4];
      q[0] = uint8_t(x * 255 / (w - 1)), q[1] = uint8_t(y * 255 / (h - 1)), q[2] = uint8_t((x * 7 + y * 13) & 255);
      q[3] = uint8_t(255 - x);
    }
  return p;
}

}  // namespace

class TestImageIo : public QObject {
  Q_OBJECT
  QTemporaryDir dir_;
  std::string path(const char* name) const { return dir_.filePath(name).toStdString(); }

 private slots:
  // First: nothing in this process has touched an image yet.
  void aMissingModuleIsNamed() {
    QVERIFY(!openImageIoMapped());
    const pid_t child = fork();
    QVERIFY(child >= 0);
    if (child == 0) {
      ::setenv("HS_IMAGE_IO_MODULE", "/nonexistent/hybridscape-image-io.so", 1);
      std::string error;
      const bool opened = io::open(path("any.png"), error) != nullptr;
      std::vector<uint8_t> bytes;
      std::string error2;
      const uint8_t pixel[4] = {1, 2, 3, 4};
      const bool encoded = io::encode("png", io::Spec::of(1, 1, 4, io::PixelType::UInt8), io::PixelType::UInt8, pixel, bytes, error2);
      const bool named = error.find("/nonexistent/hybridscape-image-io.so (not there)") != std::string::npos &&
                         error.find("HS_IMAGE_IO_MODULE") != std::string::npos && error == error2;
      _exit(!opened && !encoded && !io::available() && named ? 0 : 1);
    }
    int status = 0;
    QCOMPARE(waitpid(child, &status, 0), child);
    QVERIFY(WIFEXITED(status));
    QCOMPARE(WEXITSTATUS(status), 0);
  }

  void openImageIoIsLoadedOnTheFirstImageOnly() {
    QVERIFY2(!openImageIoMapped(), "OpenImageIO was mapped before any image call");
    std::string where;
    QVERIFY2(io::available(&where), where.c_str());
    QVERIFY(where.find("hybridscape-image-io.so") != std::string::npos);
    QVERIFY(openImageIoMapped());
  }

  void programsDoNotLinkOpenImageIo() {
    std::vector<const char*> programs = {"/cli/hybridscape-cli", "/tools/import_worker/hybridscape-import-worker"};
#ifdef HS_EDITOR_BUILT
    programs.push_back("/app/hybridscape");
#endif
    for (const char* program : programs) {
      const QByteArray libs = test::librariesOf(QString(HS_BINARY_DIR) + program);
      QVERIFY2(libs.contains("libc.so"), program);  // the listing worked (and finished)
      QVERIFY2(!libs.contains("libOpenImageIO"), program);
    }
  }

  // Alpha below 1 in the test image: OpenImageIO's default would multiply
  // it into the colour on reading and divide it out on writing.
  void pngAgreesWithQtBothWays() {
    const int w = 37, h = 23;
    const std::vector<uint8_t> rgba = gradientRgba(w, h);
    std::vector<uint8_t> png;
    std::string error;
    QVERIFY2(io::encode("png", io::Spec::of(w, h, 4, io::PixelType::UInt8), io::PixelType::UInt8, rgba.data(), png, error),
             error.c_str());
    QImage decoded = QImage::fromData(png.data(), int(png.size()), "PNG").convertToFormat(QImage::Format_RGBA8888);
    QCOMPARE(decoded.width(), w);
    QCOMPARE(decoded.height(), h);
    for (int y = 0; y < h; ++y)
      QVERIFY(std::memcmp(decoded.constScanLine(y), &rgba[size_t(y) * size_t(w) * 4], size_t(w) * 4) == 0);

    // Qt writes, we read.
    QImage made(w, h, QImage::Format_RGBA8888);
    for (int y = 0; y < h; ++y) std::memcpy(made.scanLine(y), &rgba[size_t(y) * size_t(w) * 4], size_t(w) * 4);
    QByteArray qtPng;
    QBuffer buffer(&qtPng);
    QVERIFY(made.save(&buffer, "PNG"));
    const std::span<const uint8_t> bytes(reinterpret_cast<const uint8_t*>(qtPng.constData()), size_t(qtPng.size()));
    auto in = io::openMemory(bytes, "embedded.png", error);
    QVERIFY2(in, error.c_str());
    QCOMPARE(in->spec().width, w);
    QCOMPARE(in->spec().channels, 4);
    QCOMPARE(in->spec().format, io::PixelType::UInt8);
    std::vector<uint8_t> back(rgba.size());
    QVERIFY2(in->read(4, io::PixelType::UInt8, back.data(), error), error.c_str());
    QVERIFY(back == rgba);
  }

  void sixteenBitAndFloatFilesKeepTheirValuesAndMetadata() {
    const int w = 300, h = 2;
    std::vector<uint16_t> ramp(size_t(w) * size_t(h));
    for (size_t i = 0; i < ramp.size(); ++i) ramp[i] = uint16_t(i * 219 % 65536);
    std::string error;
    io::Spec png16 = io::Spec::of(w, h, 1, io::PixelType::UInt16);
    png16.text = {{"ImageDescription", "ramp"}};
    QVERIFY2(io::writeFile(path("ramp.png"), png16, io::PixelType::UInt16, ramp.data(), error), error.c_str());
    auto in = io::open(path("ramp.png"), error);
    QVERIFY2(in, error.c_str());
    QCOMPARE(in->spec().format, io::PixelType::UInt16);
    QCOMPARE(in->spec().attribute("ImageDescription"), std::string("ramp"));
    std::vector<uint16_t> back(ramp.size());
    QVERIFY2(in->read(1, io::PixelType::UInt16, back.data(), error), error.c_str());
    QVERIFY(back == ramp);
    // As float: normalised to 0..1.
    std::vector<float> asFloat(ramp.size());
    QVERIFY2(io::open(path("ramp.png"), error)->read(1, io::PixelType::Float, asFloat.data(), error), error.c_str());
    for (size_t i = 0; i < ramp.size(); ++i) QVERIFY(std::abs(asFloat[i] - float(ramp[i]) / 65535.0f) < 1e-6f);

    std::vector<float> heights(size_t(w) * size_t(h));
    for (size_t i = 0; i < heights.size(); ++i) heights[i] = float(std::sin(double(i) * 0.37) * 1234.5678 - 17.0);
    io::Spec exr = io::Spec::of(w, h, 1, io::PixelType::Float);
    exr.channelNames = {"Y"};
    exr.text = {{"compression", "zip"}, {"hs:origin_x", "656059.25"}};
    QVERIFY2(io::writeFile(path("h.exr"), exr, io::PixelType::Float, heights.data(), error), error.c_str());
    in = io::open(path("h.exr"), error);
    QVERIFY2(in, error.c_str());
    QCOMPARE(in->spec().format, io::PixelType::Float);
    QCOMPARE(in->spec().channelNames, std::vector<std::string>{"Y"});
    QCOMPARE(in->spec().attribute("hs:origin_x"), std::string("656059.25"));
    QCOMPARE(in->spec().attribute("no such attribute"), std::string());
    std::vector<float> hb(heights.size());
    QVERIFY2(in->read(1, io::PixelType::Float, hb.data(), error), error.c_str());
    QVERIFY(hb == heights);
  }

  void tiffIsExactAndJpegWithinItsLoss() {
    // Smooth content (JPEG's loss is in the edges).
    const int w = 64, h = 48;
    std::vector<uint8_t> rgb(size_t(w) * size_t(h) * 3);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        uint8_t* q = &rgb[(size_t(y) * size_t(w) + size_t(x)) * 3];
        q[0] = uint8_t(x * 4), q[1] = uint8_t(y * 5), q[2] = uint8_t(128 + 100 * std::sin(x * 0.1 + y * 0.05));
      }
    std::string error;
    for (const char* format : {"tiff", "jpeg"}) {
      io::Spec spec = io::Spec::of(w, h, 3, io::PixelType::UInt8);
      spec.ints = {{"CompressionQuality", 95}};
      std::vector<uint8_t> bytes;
      QVERIFY2(io::encode(format, spec, io::PixelType::UInt8, rgb.data(), bytes, error), error.c_str());
      auto in = io::openMemory(bytes, std::string("frame.") + (format[0] == 't' ? "tif" : "jpg"), error);
      QVERIFY2(in, error.c_str());
      std::vector<uint8_t> back(rgb.size());
      QVERIFY2(in->read(3, io::PixelType::UInt8, back.data(), error), error.c_str());
      double sum = 0;
      for (size_t i = 0; i < rgb.size(); ++i) sum += std::abs(int(back[i]) - int(rgb[i]));
      if (format[0] == 't') QVERIFY(back == rgb);
      else QVERIFY2(sum / double(rgb.size()) < 2.0, qPrintable(QString::number(sum / double(rgb.size()))));
    }
  }

  void badInputIsAnError() {
    std::string error;
    QVERIFY(!io::open(path("missing.png"), error));
    QVERIFY(!error.empty());
    const std::vector<uint8_t> noise(1000, 0x5a);
    error.clear();
    QVERIFY(!io::openMemory(noise, "embedded.png", error));
    QVERIFY(!error.empty());

    // A PNG cut in half: the header reads, the pixels do not.
    const int w = 200, h = 200;
    const std::vector<uint8_t> rgba = gradientRgba(w, h);
    std::vector<uint8_t> png;
    QVERIFY(io::encode("png", io::Spec::of(w, h, 4, io::PixelType::UInt8), io::PixelType::UInt8, rgba.data(), png, error));
    png.resize(png.size() / 2);
    auto in = io::openMemory(png, "cut.png", error);
    QVERIFY2(in, error.c_str());
    std::vector<uint8_t> back(rgba.size());
    error.clear();
    QVERIFY(!in->read(4, io::PixelType::UInt8, back.data(), error));
    QVERIFY(!error.empty());

    const uint8_t pixel[4] = {1, 2, 3, 4};
    QVERIFY(!io::writeFile(path("x.unknownformat"), io::Spec::of(1, 1, 4, io::PixelType::UInt8), io::PixelType::UInt8, pixel,
                           error));
    QVERIFY2(error.find("cannot write this image format") == 0, error.c_str());
    QVERIFY(!io::writeFile(path("no/such/folder/x.png"), io::Spec::of(1, 1, 4, io::PixelType::UInt8), io::PixelType::UInt8,
                           pixel, error));
    QVERIFY2(error.find("cannot create the file") == 0, error.c_str());
    QVERIFY(!io::encode("no-such-format", io::Spec::of(1, 1, 4, io::PixelType::UInt8), io::PixelType::UInt8, pixel, png,
                        error));
    QVERIFY(!error.empty());
  }
};

QTEST_GUILESS_MAIN(TestImageIo)
#include "test_image_io.moc"
