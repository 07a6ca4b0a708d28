#!/usr/bin/env bash
# Packs the renderer's benchmarks, the decimation benchmark (a CPU one: the
# device machine is a quiet one, where this project's machines are shared) and
# the Debian 12 shared libraries they need into one archive that runs on a
# machine without Qt, OpenMesh, Assimp or OpenImageIO (the device machine: see
# bench/gpu/README.md):
#
#   bench/gpu/make_bundle.sh [BUILD_DIR]      # default: build/
#   -> .gpubundle/hs-gpu-bundle.tar.xz        (ignored through .gitignore)
#
# Layout of the archive (one folder, hs-gpu/):
#   bin/           the benchmarks (stripped copies; bench/gpu/run_benches.sh lists them)
#   lib/           every library they load, but glibc's, libstdc++ and libgcc_s
#                  (the host's, newer, are used), with glvnd's loaders (libEGL,
#                  libOpenGL, libGLdispatch, libGL, libGLX, libGLESv2) that libepoxy
#                  dlopens; not the image module (hybridscape-image-io.so: OpenImageIO
#                  and its ~260 libraries, core/image_io.h), so a benchmark that reads
#                  or writes an image says "the image module ... is missing"
#   lib-fallback/  libstdc++ and libgcc_s, used only where the host's are older
#   plugins/       Qt's offscreen platform (the plots' QGuiApplication)
#   fonts/         DejaVu Sans and a relocatable fonts.conf, for the plots' text
#   MANIFEST       what was packed, from which commit, the source folder baked into
#                  bench_oit (HS_SOURCE_DIR), and the newest glibc symbol version needed
#
# Libraries are found with ldd on this machine (Debian 12), so this runs where the
# build was made. Needs xz.
set -euo pipefail

root=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
out_dir=$root/.gpubundle
benches="bench/render/bench_render bench/render/bench_mesh_lod bench/render/bench_frame
bench/render/bench_shading bench/render/bench_shadows bench/render/bench_environment
bench/render/bench_lights bench/render/bench_ao bench/render/bench_dof bench/render/bench_instances bench/oit/bench_oit
bench/decimate/bench_decimate"
libdir=/usr/lib/x86_64-linux-gnu
# glvnd's loaders: dlopened by libepoxy (libEGL.so.1, libOpenGL.so.0, libGL.so.1), not in ldd.
glvnd="libEGL.so.1 libOpenGL.so.0 libGLdispatch.so.0 libGL.so.1 libGLX.so.0 libGLESv2.so.2"
qpa=$libdir/qt6/plugins/platforms/libqoffscreen.so
fonts="/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf /usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"
# Never packed: the host's C library and loader (glibc), and the C++ runtime (into lib-fallback).
glibc_re='^(linux-vdso\.so|ld-linux-x86-64\.so|libc\.so|libm\.so|libdl\.so|libpthread\.so|librt\.so|libresolv\.so|libutil\.so|libanl\.so|libmvec\.so|libnsl\.so|libBrokenLocale\.so|libnss_)'
cxxrt_re='^(libstdc\+\+\.so|libgcc_s\.so)'

for b in $benches; do
  [ -x "$build/$b" ] || { echo "make_bundle: $build/$b is missing: cmake --build $build --target $(basename "$b")" >&2; exit 1; }
done
for f in $qpa $fonts; do [ -f "$f" ] || { echo "make_bundle: $f is missing" >&2; exit 1; }; done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
stage=$work/hs-gpu
mkdir -p "$stage"/{bin,lib,lib-fallback,plugins/platforms,fonts}

# 1. The benchmarks.
for b in $benches; do
  cp "$build/$b" "$stage/bin/"
  strip --strip-unneeded "$stage/bin/$(basename "$b")"
done
cp "$qpa" "$stage/plugins/platforms/"

# 2. Every library they and the plugin load (ldd), plus glvnd's loaders.
roots="$(for b in $benches; do echo "$build/$b"; done) $qpa $(for g in $glvnd; do echo $libdir/$g; done)"
for r in $roots; do
  [ -e "$r" ] || { echo "make_bundle: $r is missing (glvnd: apt-get install libegl1 libopengl0 libgl1 libgles2)" >&2; exit 1; }
  ldd "$r" | awk '/=> not found/ {print "MISSING " $1} /=> \// {print $1 " " $3}'
done | sort -u > "$work/deps.txt"
if grep -q '^MISSING' "$work/deps.txt"; then grep '^MISSING' "$work/deps.txt" >&2; exit 1; fi
for g in $glvnd; do echo "$g $libdir/$g"; done >> "$work/deps.txt"
sort -u -o "$work/deps.txt" "$work/deps.txt"
while read -r name path; do
  if [[ $name =~ $glibc_re ]]; then continue; fi
  if [[ $name =~ $cxxrt_re ]]; then dest=lib-fallback; else dest=lib; fi
  cp -L "$path" "$stage/$dest/$name"
done < "$work/deps.txt"

# 3. Fonts for the plots: a fonts.conf whose folder is its own (prefix="relative").
cp $fonts "$stage/fonts/"
cat > "$stage/fonts/fonts.conf" <<'EOF'
<?xml version="1.0"?>
<!DOCTYPE fontconfig SYSTEM "urn:fontconfig:fonts.dtd">
<fontconfig>
  <dir prefix="relative">.</dir>
  <cachedir>/tmp/hs-gpu-fontconfig-cache</cachedir>
</fontconfig>
EOF

# 4. The manifest: what is here, and what the host must provide.
glibc_max=$(for f in "$stage"/bin/* "$stage"/lib/* "$stage"/plugins/platforms/*; do objdump -T "$f"; done |
  grep -oE '\(GLIBC_2\.[0-9]+\)' | tr -d '()' | sort -uV | tail -1)
glibcxx_max=$(for f in "$stage"/bin/* "$stage"/lib/* "$stage"/plugins/platforms/*; do objdump -T "$f"; done |
  grep -oE '\(GLIBCXX_3\.4\.[0-9]+\)' | tr -d '()' | sort -uV | tail -1)
source_dir=$(strings "$build/bench/oit/bench_oit" | grep -m1 -oE '^/.*/resources/demo/stanford-bunny\.obj$' |
  sed 's|/resources/demo/stanford-bunny\.obj$||' || true)
{
  echo "made $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(. /etc/os-release && echo "$PRETTY_NAME")"
  echo "commit $(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet HEAD -- . ':!bench/gpu' || echo ' (with uncommitted changes)')"
  echo "build $build"
  echo "source_dir $source_dir"
  echo "glibc_max $glibc_max"
  echo "glibcxx_max $glibcxx_max"
  echo "benches $(cd "$stage/bin" && echo *)"
  echo "libs $(ls "$stage/lib" | wc -l) in lib/, $(du -sm "$stage/lib" | cut -f1) MB"
} > "$stage/MANIFEST"

mkdir -p "$out_dir"
tar -C "$work" -cf - hs-gpu | xz -9 -T1 > "$out_dir/hs-gpu-bundle.tar.xz.part"
mv "$out_dir/hs-gpu-bundle.tar.xz.part" "$out_dir/hs-gpu-bundle.tar.xz"
cat "$stage/MANIFEST"
echo "bundle: $out_dir/hs-gpu-bundle.tar.xz, $(du -m "$out_dir/hs-gpu-bundle.tar.xz" | cut -f1) MB ($(du -sm "$stage" | cut -f1) MB unpacked)"
