// A stand-in for libOpenImageIO.so.2.4 and libOpenImageIO_Util.so.2.4, for
// the GPU benchmark bundle only (bench/gpu/make_bundle.sh; never linked into
// a build). The real libraries pull in some 260 others (opencv, ffmpeg,
// gdal...), 388 MB that cannot travel to the device machine; the benchmarks
// reference five of their symbols, all for decoding textures
// (mesh/texture_decode.cpp), which their scenes never do.
//
// Built from the real headers, so the two vtables the benchmarks copy
// (IOProxy, IOMemReader) have the real layout. Every call that would decode
// an image fails, and says so on stderr with the marker "HS-OIIO-STUB", which
// bench/gpu/run_benches.sh looks for in every log: a benchmark that loads
// images is reported, not silently measured without them.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstring>

OIIO_NAMESPACE_BEGIN

namespace {
const char* kMessage = "HS-OIIO-STUB: OpenImageIO is a stub in this bundle; no image can be decoded";
void report(const char* what, const std::string& name) {
  std::fprintf(stderr, "HS-OIIO-STUB: %s called (%s); returning failure\n", what, name.c_str());
}
}  // namespace

#ifdef HS_OIIO_STUB_UTIL
// libOpenImageIO_Util: the out-of-line virtual functions of the two proxies,
// which emit their vtables here.
namespace Filesystem {
size_t IOProxy::read(void*, size_t) { return 0; }
size_t IOProxy::write(const void*, size_t) { return 0; }
size_t IOProxy::pread(void*, size_t, int64_t) { return 0; }
size_t IOProxy::pwrite(const void*, size_t, int64_t) { return 0; }

size_t IOMemReader::read(void* buf, size_t size) {
  const size_t n = pread(buf, size, m_pos);
  m_pos += int64_t(n);
  return n;
}
size_t IOMemReader::pread(void* buf, size_t size, int64_t offset) {
  if (offset < 0 || size_t(offset) >= m_buf.size()) return 0;
  const size_t n = std::min(size, m_buf.size() - size_t(offset));
  std::memcpy(buf, m_buf.data() + offset, n);
  return n;
}
}  // namespace Filesystem
#else
// libOpenImageIO: opening an image always fails.
std::unique_ptr<ImageInput> ImageInput::open(const std::string& filename, const ImageSpec*, Filesystem::IOProxy*) {
  report("ImageInput::open", filename);
  return nullptr;
}
std::string ImageInput::geterror(bool) const { return kMessage; }
std::string geterror(bool) {
  report("OIIO::geterror", "");
  return kMessage;
}
#endif

OIIO_NAMESPACE_END
