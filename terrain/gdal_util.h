#pragma once
// GDAL plumbing shared by import and export: registration, RAII handles, and
// capture of GDAL's error messages so they end up in our error strings (and
// not on stderr).
#include <memory>
#include <string>
#include <vector>

#include <gdal.h>

namespace hs::terrain {

void ensureGdalRegistered();

struct DatasetCloser {
  void operator()(void* ds) const {
    if (ds) GDALClose(ds);
  }
};
using DatasetPtr = std::unique_ptr<void, DatasetCloser>;

// Collects CE_Failure/CE_Fatal (and warnings) raised on this thread while alive.
class GdalErrorCapture {
 public:
  GdalErrorCapture();
  ~GdalErrorCapture();
  GdalErrorCapture(const GdalErrorCapture&) = delete;
  GdalErrorCapture& operator=(const GdalErrorCapture&) = delete;
  // The last failure message, or "" if none.
  std::string lastError() const;
  // The first message saying that reading the file failed: any failure, or
  // a warning of an I/O error (libtiff warns "IO error during reading of
  // ...; tag ignored" and goes on); "" if none.
  std::string firstReadProblem() const;
  const std::vector<std::string>& warnings() const { return warnings_; }
  void clear() {
    errors_.clear();
    warnings_.clear();
  }

 private:
  static void handler(CPLErr cls, CPLErrorNum num, const char* msg);
  std::vector<std::string> errors_, warnings_;
};

}  // namespace hs::terrain
