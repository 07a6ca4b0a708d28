#pragma once
// The wait cursor while work runs on the UI thread (a scope's length):
// what is too short for a worker with progress, a second or so at most.
#include <QCursor>
#include <QGuiApplication>

namespace hs::app {

struct BusyCursor {
  BusyCursor() { QGuiApplication::setOverrideCursor(QCursor(Qt::WaitCursor)); }
  ~BusyCursor() { QGuiApplication::restoreOverrideCursor(); }
  BusyCursor(const BusyCursor&) = delete;
  BusyCursor& operator=(const BusyCursor&) = delete;
};

}  // namespace hs::app
