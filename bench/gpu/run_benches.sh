#!/usr/bin/env bash
# Runs the renderer's benchmarks from the bundle of bench/gpu/make_bundle.sh on
# a machine with an NVIDIA GPU and no Debian libraries (the device machine;
# bench/gpu/README.md says how to call it), one log per benchmark:
#
#   bench/gpu/run_benches.sh OUTDIR            # the GPU arguments (a few minutes)
#   bench/gpu/run_benches.sh --quick OUTDIR    # tiny arguments: checks the bundle
#
# Environment:
#   HS_GPU_BUNDLE     the archive (default .gpubundle/hs-gpu-bundle.tar.xz beside this repo's root)
#   HS_GPU_DEADLINE_S seconds for all the benchmarks together (default 330): each gets
#                     its own timeout, cut to what is left, and those that no longer
#                     fit are skipped (in the order below: the most wanted first)
#   HS_GPU_ONLY       space-separated benchmark names to run (default all)
#   HS_GPU_SYSTEM     a build folder: run its binaries on this machine's libraries instead
#                     of the bundle's (the reference of bench/gpu/check_bundle.sh)
#   HS_GPU_ALLOW_SOFTWARE=1  accept a software renderer (llvmpipe): for testing the
#                     bundle on a machine without a GPU; otherwise it is an error
#
# OUTDIR gets: summary.txt (also printed), and logs.tar.gz with every benchmark's
# log (stdout and stderr), the plots, the probe's LD_DEBUG=libs trace, the
# bundle's MANIFEST and nvidia-smi's report. Exit status: 0 when every benchmark
# ran on a hardware renderer and exited 0; 3 when no OpenGL context could be made
# or the renderer is software; 1 when any benchmark failed or timed out.
set -uo pipefail

quick=0
if [ "${1:-}" = "--quick" ]; then quick=1; shift; fi
out=${1:?usage: run_benches.sh [--quick] OUTDIR}
mkdir -p "$out"
out=$(cd "$out" && pwd)
root=$(cd "$(dirname "$0")/../.." && pwd)
bundle=${HS_GPU_BUNDLE:-$root/.gpubundle/hs-gpu-bundle.tar.xz}
deadline_s=${HS_GPU_DEADLINE_S:-330}
t0=$(date +%s)
work=$(mktemp -d /tmp/hs-gpu-run.XXXXXX)
logs=$work/logs
mkdir -p "$logs"
summary=$logs/summary.txt
say() { echo "$*" | tee -a "$summary"; }
finish() {
  cp "$summary" "$out/summary.txt"
  tar -C "$work" -czf "$out/logs.tar.gz" logs
  rm -rf "$work"
  echo "results: $out/summary.txt, $out/logs.tar.gz"
  exit "$1"
}

say "# run_benches.sh $([ $quick = 1 ] && echo --quick) at $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(hostname)"

# 1. Unpack the bundle (tar -J needs the xz program; Python's tarfile where it is missing).
#    HS_GPU_SYSTEM=BUILD_DIR instead runs that build's own binaries on this machine's
#    libraries (and image module): the reference bench/gpu/check_bundle.sh compares with.
B=$work/hs-gpu
if [ -n "${HS_GPU_SYSTEM:-}" ]; then
  mkdir -p "$B/bin"
  for f in "$HS_GPU_SYSTEM"/bench/render/bench_* "$HS_GPU_SYSTEM"/bench/oit/bench_oit "$HS_GPU_SYSTEM"/bench/decimate/bench_decimate; do ln -s "$(cd "$(dirname "$f")" && pwd)/$(basename "$f")" "$B/bin/"; done
  echo "system build $HS_GPU_SYSTEM, this machine's libraries" > "$B/MANIFEST"
else
  [ -f "$bundle" ] || { say "FAIL: no bundle at $bundle (bench/gpu/make_bundle.sh makes it)"; finish 3; }
  if command -v xz >/dev/null; then
    tar -C "$work" -xJf "$bundle"
  else
    python3 -c 'import sys, tarfile; tarfile.open(sys.argv[1]).extractall(sys.argv[2])' "$bundle" "$work"
  fi
fi
[ -x "$B/bin/bench_render" ] || { say "FAIL: the bundle did not unpack into $B"; finish 3; }
cp "$B/MANIFEST" "$logs/MANIFEST"
say "bundle: $(grep -E '^(made|commit|system)' "$B/MANIFEST" | tr '\n' ';')"

# 2. The machine: OS, C library, GPU and driver.
say "host: $(. /etc/os-release 2>/dev/null && echo "$PRETTY_NAME"), kernel $(uname -r), $(nproc) CPUs, glibc $(getconf GNU_LIBC_VERSION 2>/dev/null | awk '{print $2}')"
if command -v nvidia-smi >/dev/null; then
  timeout 30 nvidia-smi > "$logs/nvidia-smi.txt" 2>&1
  timeout 30 nvidia-smi -q -d CLOCK,UTILIZATION >> "$logs/nvidia-smi.txt" 2>&1
  say "gpu: $(timeout 20 nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader 2>&1 | head -3 | tr '\n' ';')"
else
  say "gpu: no nvidia-smi on this machine"
fi
need_glibc=$(awk '/^glibc_max/ {sub("GLIBC_", "", $2); print $2}' "$B/MANIFEST")
need_glibc=${need_glibc:-0}
have_glibc=$(getconf GNU_LIBC_VERSION 2>/dev/null | awk '{print $2}')
if [ -n "$have_glibc" ] && [ "$(printf '%s\n%s\n' "$need_glibc" "$have_glibc" | sort -V | head -1)" != "$need_glibc" ]; then
  say "WARNING: the bundle needs glibc $need_glibc, this machine has $have_glibc: libraries that need the newer symbols will not load"
fi

# 3. The libraries: the bundle's first; libstdc++ and libgcc_s from the host unless
#    the host's lack the bundle's newest GLIBCXX version; then the NVIDIA driver's folders.
ldconfig=$(command -v ldconfig || echo /sbin/ldconfig)
[ "$(id -u)" = 0 ] && "$ldconfig" 2>/dev/null  # driver libraries mounted after the cache was made
if [ -z "${HS_GPU_SYSTEM:-}" ]; then
  ldpath=$B/lib
  need_cxx=$(awk '/^glibcxx_max/ {print $2}' "$B/MANIFEST")
  host_cxx=$("$ldconfig" -p 2>/dev/null | awk '/libstdc\+\+\.so\.6 .*x86-64/ {print $NF; exit}')
  if [ -z "$host_cxx" ] || ! grep -q "$need_cxx" "$host_cxx" 2>/dev/null; then
    ldpath=$ldpath:$B/lib-fallback
    say "libstdc++: the host's (${host_cxx:-none}) lacks $need_cxx: using the bundle's"
  fi
  for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib /usr/lib64/nvidia /usr/lib/x86_64-linux-gnu/nvidia; do
    [ -d "$d" ] && ldpath=$ldpath:$d
  done
  export LD_LIBRARY_PATH=$ldpath${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  export QT_PLUGIN_PATH=$B/plugins
  export FONTCONFIG_FILE=$B/fonts/fonts.conf
fi
unset DISPLAY WAYLAND_DISPLAY
# glvnd finds the NVIDIA EGL driver through its JSON file; name it where it is not
# in glvnd's own folders (/usr/share/glvnd, /etc/glvnd).
if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ]; then
  for j in /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json /usr/share/glvnd/egl_vendor.d/10_nvidia.json \
           /etc/glvnd/egl_vendor.d/10_nvidia.json; do
    if [ -f "$j" ]; then export __EGL_VENDOR_LIBRARY_FILENAMES=$j; break; fi
  done
  if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ] && [ -z "${HS_GPU_SYSTEM:-}" ]; then
    j=$(timeout 20 find /usr /etc /opt -name 10_nvidia.json -path '*egl_vendor.d*' 2>/dev/null | head -1)
    [ -n "$j" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$j
  fi
fi
# The driver's libEGL_nvidia.so.0, where neither the loader's cache nor the folders above have it.
if [ -z "${HS_GPU_SYSTEM:-}" ] && command -v nvidia-smi >/dev/null && ! "$ldconfig" -p 2>/dev/null | grep -q libEGL_nvidia.so.0; then
  found=""
  IFS=: read -ra dirs <<< "$LD_LIBRARY_PATH"
  for d in "${dirs[@]}"; do [ -e "$d/libEGL_nvidia.so.0" ] && found=$d/libEGL_nvidia.so.0; done
  if [ -z "$found" ]; then
    found=$(timeout 20 find /usr /opt /lib /lib64 -name 'libEGL_nvidia.so.0' 2>/dev/null | head -1)
    if [ -n "$found" ]; then LD_LIBRARY_PATH=$LD_LIBRARY_PATH:$(dirname "$found"); fi
  fi
  say "libEGL_nvidia.so.0: not in the loader's cache; found: ${found:-nowhere}"
fi
say "EGL vendor: ${__EGL_VENDOR_LIBRARY_FILENAMES:-the default folders of glvnd}; LD_LIBRARY_PATH=${LD_LIBRARY_PATH:-}"
{
  echo "== ldconfig -p (EGL, GL, nvidia)"; "$ldconfig" -p 2>/dev/null | grep -iE 'libEGL|libGL|nvidia' | head -40
  echo "== /usr/local/nvidia"; ls -R /usr/local/nvidia 2>&1 | head -80
  echo "== egl_vendor.d"; ls -l /usr/share/glvnd/egl_vendor.d /etc/glvnd/egl_vendor.d 2>&1
  echo "== /dev"; ls -l /dev/nvidia* /dev/dri 2>&1
} > "$logs/driver.txt" 2>&1

# The benchmarks, most wanted first: name, timeout s, GPU arguments, quick
# arguments, and the CPUs a CPU benchmark is pinned to (taskset; empty for the
# renderer's, which need an OpenGL context). Plots go to the log folder ({} is
# replaced by it). bench_decimate measures issue 11's speed target (ours on two
# threads against meshopt_simplify on one), so it gets two cores of a machine
# nothing else runs on; the bunny and the 5M scan tile, its error included.
benches=(
  "bench_render|60|--frames 300 --warmup 30|--frames 1 --warmup 0 --size 320x180|"
  "bench_oit|120|--sizes 640x480,1920x1080 --runs 30 --plot {}/bench_oit.png|--sizes 160x120 --runs 1 --plot {}/bench_oit.png|"
  "bench_frame|60|--frames 60 --rounds 5|--frames 1 --rounds 1 --size 320x180|"
  "bench_instances|120|--frames 30 --size 1920x1080|--frames 1 --size 320x180 --counts 10000|"
  "bench_shading|90|--frames 60 --warmup 10 --plot {}/bench_shading.png|--frames 1 --warmup 0 --size 320x180 --plot {}/bench_shading.png|"
  "bench_lights|60|--frames 30 --plot {}/bench_lights.png|--frames 1 --quick --plot {}/bench_lights.png|"
  "bench_mesh_lod|60|--frames 60|--frames 1 --size 320x180 --grid 3|"
  "bench_shadows|120|--frames 15 --plot {}/bench_shadows.png|--frames 1 --size 320x180 --quick --plot {}/bench_shadows.png|"
  "bench_dof|60|--frames 15 --samples 128 --plot {}/bench_dof.png|--frames 1 --size 160x120 --samples 64 --plot {}/bench_dof.png|"
  "bench_ao|90|--frames 30|--frames 1 --size 160x120 --rays 16|"
  "bench_environment|40|--frames 61|--frames 1|"
  "bench_decimate|300|--skip-quad --no-peers --no-stock --ratios 50,10,1 --runs 9 --terrain-runs 5 --plot {}/bench_decimate.png|--skip-terrain --skip-quad --no-peers --no-stock --ratios 10 --runs 1 --plot {}/bench_decimate.png|0,1"
)
selected() { [ -z "${HS_GPU_ONLY:-}" ] || [[ " $HS_GPU_ONLY " == *" $1 "* ]]; }
need_gl=0
for entry in "${benches[@]}"; do
  IFS='|' read -r name _ _ _ cpus <<< "$entry"
  selected "$name" && [ -z "$cpus" ] && need_gl=1
done

# bench_oit and bench_decimate read the bunny from the source folder baked into them (HS_SOURCE_DIR).
src=$(awk '/^source_dir/ {print $2}' "$B/MANIFEST")
if [ -n "$src" ] && [ ! -e "$src/resources/demo/stanford-bunny.obj" ]; then
  mkdir -p "$(dirname "$src")" && ln -sfn "$root" "$src" && say "linked $src -> $root (the benchmarks' HS_SOURCE_DIR)"
fi

# 4. A probe, when a renderer benchmark is chosen: one small frame. The default
#    EGL order first (Mesa surfaceless, EGL devices, the default display), then
#    HS_EGL_PLATFORM=device; it must name a hardware renderer. The probe's
#    LD_DEBUG=libs trace shows where each library came from.
is_software() { grep -qiE 'llvmpipe|softpipe|swrast|software rasterizer' "$1"; }
probe() {
  LD_DEBUG=libs LD_DEBUG_OUTPUT=$logs/probe-$1.lddebug timeout -k 5 60 \
    "$B/bin/bench_render" --frames 1 --warmup 0 --size 64x64 > "$logs/probe-$1.log" 2>&1
}
egl_choice=""
for p in default device; do
  [ $need_gl = 0 ] && break
  if [ $p = device ]; then export HS_EGL_PLATFORM=device; else unset HS_EGL_PLATFORM; fi
  probe $p; rc=$?
  say "probe ($p EGL platform): exit $rc: $(grep -m1 'demo scene' "$logs/probe-$p.log" || tail -2 "$logs/probe-$p.log" | tr '\n' ' ')"
  if [ $rc = 0 ] && { ! is_software "$logs/probe-$p.log" || [ "${HS_GPU_ALLOW_SOFTWARE:-0}" = 1 ]; }; then egl_choice=$p; break; fi
done
if [ $need_gl = 0 ]; then
  say "probe: skipped (the benchmarks chosen need no OpenGL context)"
elif [ -z "$egl_choice" ]; then
  say "FAIL: no hardware OpenGL context (probe logs and LD_DEBUG traces in logs.tar.gz; driver.txt lists the driver's files)"
  finish 3
fi
if [ "$egl_choice" = device ]; then export HS_EGL_PLATFORM=device; else unset HS_EGL_PLATFORM; fi
if [ $need_gl = 1 ]; then
  from_bundle=$(grep -ohE 'calling init: /[^ ]+' "$logs/probe-$egl_choice.lddebug".* 2>/dev/null | awk '{print $3}' | sort -u)
  say "probe loaded $(echo "$from_bundle" | grep -c "^$B/lib/") libraries from the bundle, $(echo "$from_bundle" | grep -vc "^$B/" ) from the host:"
  echo "$from_bundle" | grep -v "^$B/" | sed 's/^/  host: /' | tee -a "$summary"
fi

failed=0
say ""
for entry in "${benches[@]}"; do
  IFS='|' read -r name limit gpu_args quick_args cpus <<< "$entry"
  selected "$name" || continue
  pin=()
  if [ -n "$cpus" ]; then
    if command -v taskset >/dev/null; then pin=(taskset -c "$cpus"); else say "$name: no taskset here: not pinned to CPUs $cpus"; fi
  fi
  args=$gpu_args; [ $quick = 1 ] && args=$quick_args
  args=${args//\{\}/$logs}
  left=$(( deadline_s - ($(date +%s) - t0) ))
  [ "$left" -lt "$limit" ] && limit=$left
  if [ "$limit" -lt 15 ]; then say "$name: SKIPPED (deadline: ${left} s left)"; failed=1; continue; fi
  log=$logs/$name.log
  echo "\$ ${pin[*]} $name $args   (timeout ${limit}s, HS_EGL_PLATFORM=${HS_EGL_PLATFORM:-})" > "$log"
  s=$(date +%s%N)
  # shellcheck disable=SC2086
  (cd "$logs" && timeout -k 5 "$limit" "${pin[@]}" "$B/bin/$name" $args) >> "$log" 2>&1
  rc=$?
  wall_ds=$(( ($(date +%s%N) - s) / 100000000 ))
  renderer=$(grep -m1 -E ' [|] [0-9]\.[0-9]' "$log" | cut -c1-200)
  [ -n "$cpus" ] && renderer="CPU benchmark, ${pin[*]:-not pinned}, $(grep -m1 -oE 'machine: [^)]*' "$log")"
  note=""
  [ $rc = 124 ] || [ $rc = 137 ] && note=" TIMED OUT"
  is_software "$log" && [ "${HS_GPU_ALLOW_SOFTWARE:-0}" != 1 ] && note="$note SOFTWARE RENDERER"
  # The bundle has no image module (make_bundle.sh): a benchmark that needs an image says so.
  grep -q 'image module hybridscape-image-io.so (OpenImageIO) is missing' "$log" && note="$note LOADED IMAGES (none in the bundle)"
  [ $rc != 0 ] || [ -n "$note" ] && failed=1
  say "$name: exit $rc$note, $((wall_ds / 10)).$((wall_ds % 10)) s"
  say "  ${renderer:-(no renderer line)}"
done
say ""
say "total $(( $(date +%s) - t0 )) s"
if grep -lqiE 'llvmpipe|softpipe' "$logs"/bench_*.log 2>/dev/null && [ "${HS_GPU_ALLOW_SOFTWARE:-0}" != 1 ]; then
  say "FAIL: a benchmark ran on a software renderer"
  finish 3
fi
finish $failed
