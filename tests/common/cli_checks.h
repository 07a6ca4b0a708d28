#pragma once
// Checks of one hybridscape-cli run that the CLI suites share: it worked,
// or it failed with the exit code and one line on stderr naming what it
// should. Like any Qt Test check in a helper, a failure returns from here
// only: the caller goes on and the test is reported failed.
#include <QtTest>

#include "cli_runner.h"

namespace hs::test {

inline void verifyCliOk(const CliRun& r, const QStringList& args) {
  QVERIFY2(r.code == 0, qPrintable("hybridscape-cli " + args.join(' ') + ": exit " + QString::number(r.code) + ": " + r.err));
}

inline void verifyCliError(const CliRun& r, const QStringList& args, int code, const QStringList& names) {
  const QString cmd = "hybridscape-cli " + args.join(' ');
  QVERIFY2(r.code == code,
           qPrintable(QString("%1: exit %2, expected %3; stderr: %4").arg(cmd).arg(r.code).arg(code).arg(r.err)));
  QVERIFY2(r.errLines().size() == 1, qPrintable(cmd + ": expected one line on stderr, got:\n" + r.err));
  for (const QString& n : names)
    QVERIFY2(r.err.contains(n), qPrintable(QString("%1: '%2' not in: %3").arg(cmd, n, r.err)));
}

}  // namespace hs::test
