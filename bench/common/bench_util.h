#pragma once
// Small helpers every benchmark shares: clocks, medians and percentiles,
// the machine's load (the machines are shared, so each table says how busy
// the machine was while it was measured) and CPU time.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "core/parallel.h"

namespace hs::bench {

// The machine's hardware threads, and how many of them this process may
// use when that is fewer (taskset, a Slurm binding: bench/gpu pins
// bench_decimate to two CPUs of sixteen).
inline std::string threadsText() {
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency()), allowed = allowedCpus();
  std::string s = std::to_string(hw) + " hardware threads";
  if (allowed < hw) s += ", " + std::to_string(allowed) + " of them allowed to this process";
  return s;
}

// A field of /proc/self/status in KiB ("VmRSS:" resident now, "VmHWM:" its
// peak); 0 when it is not there.
inline size_t statusKiB(const char* field) {
  std::ifstream f("/proc/self/status");
  std::string line;
  const std::string key(field);
  while (std::getline(f, line))
    if (line.compare(0, key.size(), key) == 0) return size_t(std::strtoull(line.c_str() + key.size(), nullptr, 10));
  return 0;
}

inline double nowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5))];
}

// A comma-separated list of numbers ("50,10,1"), each divided by `divisor`
// (100: percentages as ratios); an empty item reads as 0. The benchmarks'
// --ratios and similar options.
inline std::vector<double> numberList(const std::string& list, double divisor = 1.0) {
  std::vector<double> v;
  for (size_t p = 0; p < list.size();) {
    const size_t q = list.find(',', p);
    v.push_back(std::atof(list.substr(p, q - p).c_str()) / divisor);
    p = q == std::string::npos ? list.size() : q + 1;
  }
  return v;
}

// The 1-minute load average (-1 if unknown).
inline double loadAverage() {
  double l = -1.0;
  std::ifstream("/proc/loadavg") >> l;
  return l;
}

// /proc/loadavg as it stands: the 1, 5 and 15-minute averages and the
// running/total tasks.
inline std::string loadAverageLine() {
  std::ifstream f("/proc/loadavg");
  std::string line;
  std::getline(f, line);
  return line;
}

// CPU time (user + system) of this process (RUSAGE_SELF) or of its
// waited-for children (RUSAGE_CHILDREN, e.g. ffmpeg). Wall times move with
// other people's load, CPU time much less.
inline double cpuSeconds(int who) {
  rusage u{};
  getrusage(who, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + double(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6;
}

}  // namespace hs::bench
