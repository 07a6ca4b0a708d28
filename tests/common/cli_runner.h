#pragma once
// hybridscape-cli run as a user runs it, for the suites that drive the built
// program: QProcess in a working directory, with a time limit, its exit code
// and both output streams kept. Header-only, Qt Core only.
#include <QProcess>
#include <QString>
#include <QStringList>
#include <QtGlobal>

#include <functional>

namespace hs::test {

// The built program (the suite's CMake target depends on it).
inline const QString kCli = QStringLiteral(HS_BINARY_DIR "/cli/hybridscape-cli");

// One run of the program.
struct CliRun {
  int code = -1;  // the exit code; -1 if it crashed or did not finish in time
  QString out, err;
  // stderr as lines, without the final newline's empty tail.
  QStringList errLines() const { return err.split('\n', Qt::SkipEmptyParts); }
};

// Runs hybridscape-cli with `args` in `workDir` (the test's environment) and
// waits up to `timeoutMs`; a run that does not finish by then is killed,
// reported with a warning, and comes back with code -1 and no output.
// `inChild`, when given, runs in the child before exec (QProcess's child
// process modifier: system calls only, e.g. binding it to a CPU).
inline CliRun runCli(const QStringList& args, const QString& workDir, int timeoutMs = 120000,
                     const std::function<void()>& inChild = {}) {
  QProcess p;
  p.setWorkingDirectory(workDir);
  if (inChild) p.setChildProcessModifier(inChild);
  p.start(kCli, args);
  CliRun r;
  if (!p.waitForFinished(timeoutMs)) {
    p.kill();
    p.waitForFinished();
    qWarning("hybridscape-cli %s did not finish", qPrintable(args.join(' ')));
    return r;
  }
  r.code = p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1;
  r.out = QString::fromLocal8Bit(p.readAllStandardOutput());
  r.err = QString::fromLocal8Bit(p.readAllStandardError());
  return r;
}

// `hybridscape-cli new <file>` run in `workDir`: an empty scene to work on.
// Returns `file`; a failure is reported with a warning (the test then fails
// on the missing or unreadable scene).
inline QString newSceneWithCli(const QString& file, const QString& workDir) {
  const CliRun r = runCli({"new", file}, workDir);
  if (r.code != 0) qWarning("new: %s", qPrintable(r.err));
  return file;
}

}  // namespace hs::test
