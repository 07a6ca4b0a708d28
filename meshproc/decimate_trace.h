#pragma once
// Step timings of the decimator on stderr when HS_DECIMATE_TRACE is set
// (wall and process CPU seconds since the previous mark; with
// HS_DECIMATE_ROUNDS also every round's work): for profiling, off
// otherwise. Shared by the setup (decimate.cpp), the parallel schedule
// (region_levels.cpp) and the minimax refinement (max_error_refine.cpp).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include <sys/resource.h>

namespace hs::mesh {

using DecimateClock = std::chrono::steady_clock;

inline double secondsSince(DecimateClock::time_point t) {
  return std::chrono::duration<double>(DecimateClock::now() - t).count();
}

inline double processCpuNow() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

inline double threadCpuNow() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

struct DecimateTrace {
  bool on = std::getenv("HS_DECIMATE_TRACE") != nullptr;
  bool rounds = on && std::getenv("HS_DECIMATE_ROUNDS") != nullptr;
  DecimateClock::time_point wall = DecimateClock::now();
  double cpu = processCpuNow();
  long faults = minorFaults();
  void mark(const char* what) {
    if (!on) return;
    const double c = processCpuNow();
    const long f = minorFaults();
    std::fprintf(stderr, "  [decimate] %-28s wall %7.3f  cpu %7.3f  rss %6.0f MB  faults %6ld\n", what,
                 secondsSince(wall), c - cpu, residentMB(), f - faults);
    wall = DecimateClock::now(), cpu = c, faults = f;
  }
  static long minorFaults() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_minflt;
  }
  // The process's resident memory (Linux: /proc/self/statm), -1 elsewhere.
  static double residentMB() {
    double pages = -1;
    if (FILE* f = std::fopen("/proc/self/statm", "r")) {
      double size = 0;
      if (std::fscanf(f, "%lf %lf", &size, &pages) != 2) pages = -1;
      std::fclose(f);
    }
    return pages < 0 ? -1 : pages * 4096.0 / 1048576.0;
  }
};

}  // namespace hs::mesh
