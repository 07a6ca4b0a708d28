#pragma once
// Which shared libraries a process has: the suites of the module doors
// (test_image_io, test_terrain_gdal_door) check that a heavy library is
// mapped only after its first use and that no program links it.
#include <QByteArray>
#include <QProcess>
#include <QProcessEnvironment>
#include <QString>

#include <fstream>
#include <sstream>
#include <string>

namespace hs::test {

// Whether a library whose path contains `name` is mapped in this process.
inline bool mappedHere(const std::string& name) {
  std::ifstream maps("/proc/self/maps");
  std::ostringstream s;
  s << maps.rdbuf();
  return s.str().find(name) != std::string::npos;
}

// What `program` needs, as the dynamic loader lists it (ldd's own
// mechanism: LD_TRACE_LOADED_OBJECTS lists and exits without running the
// program); empty when it did not finish within 30 s.
inline QByteArray librariesOf(const QString& program) {
  QProcess p;
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.insert("LD_TRACE_LOADED_OBJECTS", "1");
  p.setProcessEnvironment(env);
  p.start(program, {});
  if (!p.waitForFinished(30000)) return {};
  return p.readAllStandardOutput();
}

}  // namespace hs::test
