#include "terrain/gdal_util.h"

#include <mutex>

#include <cpl_error.h>

namespace hs::terrain {

void ensureGdalRegistered() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

GdalErrorCapture::GdalErrorCapture() { CPLPushErrorHandlerEx(&GdalErrorCapture::handler, this); }
GdalErrorCapture::~GdalErrorCapture() { CPLPopErrorHandler(); }

void GdalErrorCapture::handler(CPLErr cls, CPLErrorNum, const char* msg) {
  auto* self = static_cast<GdalErrorCapture*>(CPLGetErrorHandlerUserData());
  if (!self) return;
  if (cls == CE_Failure || cls == CE_Fatal)
    self->errors_.emplace_back(msg ? msg : "");
  else if (cls == CE_Warning)
    self->warnings_.emplace_back(msg ? msg : "");
}

std::string GdalErrorCapture::lastError() const { return errors_.empty() ? std::string() : errors_.back(); }

std::string GdalErrorCapture::firstReadProblem() const {
  if (!errors_.empty()) return errors_.front();
  for (const std::string& w : warnings_)
    for (const char* sign : {"IO error", "I/O error", "Read error", "read error"})
      if (w.find(sign) != std::string::npos) return w;
  return {};
}

}  // namespace hs::terrain
