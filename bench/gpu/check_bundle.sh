#!/usr/bin/env bash
# Checks the bundle of make_bundle.sh on this machine (llvmpipe), before it
# travels: every benchmark of run_benches.sh, with its tiny --quick arguments,
#   A. from the unpacked bundle, in an empty environment (env -i: nothing but
#      PATH and HOME), so only the bundle's libraries and the host's glibc,
#      libstdc++ and Mesa can be found, and
#   B. from the build folder on this machine's libraries (with the image module),
# then compares the two logs of each with the timings masked (compare_logs.py):
# triangle counts, draw calls, image errors, memory must be identical, and no
# benchmark may need an image (the bundle has no image module; run_benches.sh
# flags "LOADED IMAGES").
#
#   bench/gpu/check_bundle.sh [BUILD_DIR] [OUTDIR]     # about 2.5 min of CPU on 2 cores
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../build}" && pwd)
out=${2:-$(mktemp -d /tmp/hs-gpu-check.XXXXXX)}
mkdir -p "$out/bundle" "$out/system"

env -i PATH=/usr/bin:/bin HOME=/tmp HS_GPU_ALLOW_SOFTWARE=1 nice -n 15 \
  "$here/run_benches.sh" --quick "$out/bundle" > "$out/bundle.out" 2>&1
rc_a=$?
HS_GPU_SYSTEM=$build HS_GPU_ALLOW_SOFTWARE=1 nice -n 15 \
  "$here/run_benches.sh" --quick "$out/system" > "$out/system.out" 2>&1
rc_b=$?
for d in bundle system; do mkdir -p "$out/$d/x" && tar -C "$out/$d/x" -xzf "$out/$d/logs.tar.gz"; done

status=0
echo "bundle run: exit $rc_a; system run: exit $rc_b (logs in $out)"
[ $rc_a = 0 ] && [ $rc_b = 0 ] || status=1
grep -H 'LOADED IMAGES\|SKIPPED\|TIMED OUT' "$out"/*/summary.txt && status=1
for log in "$out"/system/x/logs/bench_*.log; do
  name=$(basename "$log")
  if python3 "$here/compare_logs.py" "$out/bundle/x/logs/$name" "$log" > "$out/$name.diff"; then
    echo "$name: same (timings masked)"
  else
    echo "$name: DIFFERS"; cat "$out/$name.diff"; status=1
  fi
done
# Where each library of the bundle run came from (its probe's LD_DEBUG=libs trace).
sed -n '/^probe loaded/,/^$/p' "$out/bundle/summary.txt"
exit $status
