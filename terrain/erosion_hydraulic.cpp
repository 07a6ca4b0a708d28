#include "terrain/erosion_hydraulic.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/parallel.h"
#include "terrain/undo_step.h"

namespace hs::terrain {

ErosionReport erodeHydraulicGrid(std::vector<float>& b, int w, int hgt, glm::dvec2 spacing,
                                 const HydraulicParams& in, const float* mask, const Progress* progress,
                                 int threads, std::vector<float>* waterOut) {
  const auto t0 = std::chrono::steady_clock::now();
  ErosionReport rep;
  const HydraulicParams p = in.sanitized(rep.warnings);
  rep.iterationsRequested = p.iterations;
  rep.threads = resolveThreads(threads);
  rep.requestedTime = p.iterations * p.timeStep;
  if (w < 2 || hgt < 2 || b.size() != size_t(w) * size_t(hgt)) return rep;
  if (!(spacing.x > 0.0 && spacing.y > 0.0)) spacing = glm::dvec2(1.0);
  rep.nonFiniteHeightsFixed = detail::sanitizeHeights(b, w, hgt);
  if (rep.nonFiniteHeightsFixed)
    rep.warnings.push_back(std::to_string(rep.nonFiniteHeightsFixed) +
                           " non-finite heights replaced by the mean of their neighbours");

  const size_t n = b.size();
  const double cellArea = spacing.x * spacing.y;
  rep.massBefore = detail::sumHeights(b, w, hgt) * cellArea;
  double absSum = 0.0;
  for (float v : b) absSum += std::abs(double(v));

  std::vector<float> d(n, 0.0f), s(n, 0.0f), d2(n), s2(n), sinA(n), delta(n, 0.0f), conc(n, 0.0f);
  auto rock = [&](size_t i) { return b[i] + delta[i]; };
  std::vector<float> fL(n, 0.0f), fR(n, 0.0f), fB(n, 0.0f), fT(n, 0.0f);
  std::vector<float> rowMaxD(size_t(hgt), 0.0f), rowMaxV(size_t(hgt), 0.0f);
  const float lx = float(spacing.x), ly = float(spacing.y), area = float(cellArea);
  const float g = float(p.gravity);
  const float kcap = float(p.sedimentCapacity), minSlope = float(p.minSlope);
  const float invDepthLimit = float(1.0 / p.depthLimit);
  const float depthFloor = float(p.depthLimit);
  constexpr float kMaxFroude = 2.0f;
  const float friction = float(p.friction);
  const float rain = float(p.rain);
  auto idx = [w](int x, int y) { return size_t(y) * size_t(w) + size_t(x); };
  auto m = [&](size_t i) { return mask ? std::clamp(mask[i], 0.0f, 1.0f) : 1.0f; };
  const double minSpacing = std::min(spacing.x, spacing.y);

  float maxD = 0.0f, maxV = 0.0f;
  rep.minDt = p.timeStep;
  rep.maxDt = 0.0;
  for (int it = 0; it < p.iterations; ++it) {
    if (isCancelled(progress)) {
      rep.cancelled = true;
      break;
    }
    // CFL: the fastest signal (flow speed plus shallow-water wave speed
    // sqrt(g d)) may cross at most `cfl` of a cell per step. The depth bound
    // includes this step's rain.
    const double depthBound = double(maxD) + p.rain * p.timeStep;
    const double signal = double(maxV) + std::sqrt(p.gravity * depthBound);
    double dtd = p.timeStep;
    if (signal > 0.0 && p.cfl * minSpacing / signal < dtd) {
      dtd = p.cfl * minSpacing / signal;
      ++rep.cflLimitedIterations;
    }
    rep.minDt = std::min(rep.minDt, dtd);
    rep.maxDt = std::max(rep.maxDt, dtd);
    rep.simulatedTime += dtd;
    const float dt = float(dtd);
    const float rainStep = rain * dt;
    const float erodeK = float(std::min(p.erosionRate * dtd, 0.5));
    const float depositK = float(std::min(p.depositionRate * dtd, 1.0));
    const float evapKeep = float(std::max(0.0, 1.0 - p.evaporation * dtd));
    // Outflow may not take more water than the cell holds; the tiny margin
    // keeps rounding from letting it take a hair more.
    const float fluxScaleMargin = 0.99999f;
    auto depthAfterRain = [&](size_t i) { return d[i] + rainStep * m(i); };

    // Pass 1: outflow fluxes and local slope, from the previous state only.
    parallelFor(hgt, threads, 8, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; ++x) {
          const size_t i = idx(x, y);
          const float di = depthAfterRain(i);
          const float Hi = rock(i) + di;
          // Pipe flux: accelerated by the surface difference, slowed by bed
          // friction that grows as the water gets shallow (friction * length
          // / depth, implicit so it is stable for any step). Flow down a
          // slope S then tends to speed g * S / friction whatever the step,
          // where the paper's frictionless pipes let thin sheets run at
          // whatever speed the outflow limiter allows (about a cell per
          // step: a result that depends on dt).
          auto flux = [&](float f, int nx, int ny, float perp, float len) {
            if (nx < 0 || ny < 0 || nx >= w || ny >= hgt) return 0.0f;  // wall
            const size_t j = idx(nx, ny);
            const float dj = depthAfterRain(j);
            const float dh = Hi - (rock(j) + dj);
            const float depth = std::max(0.5f * (di + dj), depthFloor);
            return std::max(0.0f, (f + dt * g * dh * perp) / (1.0f + dt * friction * len / depth));
          };
          float l = flux(fL[i], x - 1, y, ly, lx), r = flux(fR[i], x + 1, y, ly, lx);
          float bo = flux(fB[i], x, y - 1, lx, ly), t = flux(fT[i], x, y + 1, lx, ly);
          const float sum = (l + r) + (bo + t);
          if (sum > 0.0f) {
            const float k = std::min(1.0f, di * area / (sum * dt)) * fluxScaleMargin;
            l *= k; r *= k; bo *= k; t *= k;
          }
          fL[i] = l; fR[i] = r; fB[i] = bo; fT[i] = t;
          const int xm = std::max(x - 1, 0), xp = std::min(x + 1, w - 1);
          const int ym = std::max(y - 1, 0), yp = std::min(y + 1, hgt - 1);
          const float gx = (rock(idx(xp, y)) - rock(idx(xm, y))) / (float(xp - xm) * lx);
          const float gy = (rock(idx(x, yp)) - rock(idx(x, ym))) / (float(yp - ym) * ly);
          const float g2 = gx * gx + gy * gy;
          sinA[i] = std::sqrt(g2 / (1.0f + g2));
          // A pipe carrying flux f for dt moves f * dt / (d * area) of the
          // cell's water, so that fraction of its sediment.
          conc[i] = di > 0.0f ? s[i] * (dt / (di * area)) : 0.0f;
        }
    });

    // Pass 2: water, sediment transport, erosion/deposition, evaporation.
    parallelFor(hgt, threads, 8, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y) {
        float rowD = 0.0f, rowV = 0.0f;
        for (int x = 0; x < w; ++x) {
          const size_t i = idx(x, y);
          const float di = depthAfterRain(i);
          // Sediment through a pipe = flux * (sediment per unit of water
          // volume moved in this step), the factor computed once per cell
          // in pass 1. Sender and receiver use this same product, so the
          // sediment that leaves is the sediment that arrives.
          auto share = [&](size_t j, float f) { return f * conc[j]; };
          float inW = 0.0f, inS = 0.0f, fromL = 0.0f, fromR = 0.0f, fromB = 0.0f, fromT = 0.0f;
          if (x > 0) { const size_t j = idx(x - 1, y); fromL = fR[j]; inS += share(j, fromL); }
          if (x + 1 < w) { const size_t j = idx(x + 1, y); fromR = fL[j]; inS += share(j, fromR); }
          if (y > 0) { const size_t j = idx(x, y - 1); fromB = fT[j]; inS += share(j, fromB); }
          if (y + 1 < hgt) { const size_t j = idx(x, y + 1); fromT = fB[j]; inS += share(j, fromT); }
          inW = (fromL + fromR) + (fromB + fromT);
          const float outW = (fL[i] + fR[i]) + (fB[i] + fT[i]);
          const float outS = (share(i, fL[i]) + share(i, fR[i])) + (share(i, fB[i]) + share(i, fT[i]));
          float dn = std::max(0.0f, di + dt * (inW - outW) / area);
          float sn = s[i] - outS + inS;

          // Velocity from the net flux through the cell (Mei et al., eq. 8-9).
          // Velocity from flux / depth is unbounded in a thin film; there
          // friction dominates, so the depth is taken as at least
          // depthLimit. This bounds the speeds that enter the capacity and
          // the CFL limit (thin films cannot outrun the outflow limiter).
          const float meanD = std::max(0.5f * (di + dn), depthFloor);
          float speed = 0.0f;
          {
            const float u = 0.5f * ((fromL - fL[i]) + (fR[i] - fromR)) / (ly * meanD);
            const float v = 0.5f * ((fromB - fB[i]) + (fT[i] - fromT)) / (lx * meanD);
            speed = std::sqrt(u * u + v * v);
            // Froude number at most 2: the frictionless pipe model lets a
            // thin sheet slosh at absurd speeds, which real flow (friction)
            // never reaches. Bounds the capacity and the CFL step.
            speed = std::min(speed, kMaxFroude * std::sqrt(g * meanD));
          }
          const float taper = std::min(1.0f, dn * invDepthLimit);
          const float capacity = kcap * speed * std::max(sinA[i], minSlope) * taper;
          // Rock changes accumulate in `delta` (rock = base + delta), whose
          // float resolution follows the size of the change, not of the
          // height: 1e-7 m of erosion per step still counts on a 1000 m
          // terrain, so small steps converge instead of stalling. The
          // exchange moves exactly what delta lost into the sediment.
          const float di0 = delta[i];
          if (capacity > sn) {
            const float nd = di0 - erodeK * (capacity - sn) * m(i);
            sn += di0 - nd;
            delta[i] = nd;
          } else {
            const float nd = di0 + depositK * (sn - capacity);
            sn -= nd - di0;
            delta[i] = nd;
          }
          dn *= evapKeep;
          d2[i] = dn;
          s2[i] = sn;
          rowD = std::max(rowD, dn);
          rowV = std::max(rowV, speed);
        }
        rowMaxD[size_t(y)] = rowD;
        rowMaxV[size_t(y)] = rowV;
      }
    });
    d.swap(d2);
    s.swap(s2);
    maxD = *std::max_element(rowMaxD.begin(), rowMaxD.end());
    maxV = *std::max_element(rowMaxV.begin(), rowMaxV.end());
    if (!std::isfinite(maxD) || !std::isfinite(maxV)) {
      // Cannot happen with the limits above; if it ever does, stop rather
      // than write garbage, and say so.
      rep.warnings.push_back("hydraulic erosion stopped: non-finite water state at iteration " +
                             std::to_string(it));
      rep.cancelled = true;
      break;
    }
    rep.iterationsDone = it + 1;
    if (progress && (it % 8 == 0 || it + 1 == p.iterations))
      progress->report(double(it + 1) / double(std::max(1, p.iterations)), "hydraulic erosion");
  }
  if (rep.iterationsDone == 0) rep.minDt = 0.0;

  // Suspended sediment settles where it is.
  for (size_t i = 0; i < n; ++i) b[i] = float(double(b[i]) + (double(delta[i]) + double(s[i])));
  if (waterOut) *waterOut = d;
  if (rep.cflLimitedIterations)
    rep.warnings.push_back("time step shortened by the CFL limit in " + std::to_string(rep.cflLimitedIterations) +
                           " of " + std::to_string(rep.iterationsDone) + " iterations (simulated " +
                           std::to_string(rep.simulatedTime) + " s of " + std::to_string(rep.requestedTime) + " s)");
  detail::finishReport(rep, b, w, hgt, cellArea, absSum, t0);
  return rep;
}

ErosionReport erodeHydraulic(Heightfield& hf, const HydraulicParams& params, const ErosionMask& mask,
                             UndoRecorder* recorder, const Progress* progress, int threads) {
  return detail::erodeWindow(hf, mask, recorder, [&](std::vector<float>& h, int w, int hgt, const float* weights) {
    return erodeHydraulicGrid(h, w, hgt, hf.spacing(), params, weights, progress, threads);
  });
}

}  // namespace hs::terrain
