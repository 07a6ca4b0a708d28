#!/usr/bin/env bash
# Installs the Debian 12 packages Hybridscape builds and tests with, only
# those missing. Runs apt-get as root (directly, or through sudo).
set -euo pipefail

BUILD_PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  qt6-base-dev qt6-base-dev-tools libqt6opengl6-dev libgl-dev
  libglm-dev libassimp-dev libopenimageio-dev openimageio-tools libopenmesh-dev libgdal-dev
  libepoxy-dev libegl-dev libegl-mesa0 libgl1-mesa-dri libsqlite3-dev libmeshoptimizer-dev
  libtbb-dev nlohmann-json3-dev libxxhash-dev libcli11-dev zlib1g-dev libdeflate-dev
  libcgal-dev libopencolorio-dev libtinygltf-dev libdraco-dev
)
# Tests: an X server for the GUI smoke test, Mesa for headless EGL, ffmpeg
# (and its ffprobe) for the sequencer's direct-video export test, Slurm and
# munge for the render-farm test (a one-node Slurm it starts on localhost).
TEST_PACKAGES=(xvfb xauth libgl1-mesa-dri libegl-mesa0 mesa-utils ffmpeg slurm-wlm munge)

# Fuzzing (`scripts/hs fuzz`): Debian's clang with libFuzzer and the
# sanitizer runtimes. Only that command asks for them.
FUZZ_PACKAGES=(clang libclang-rt-14-dev)

want=("${BUILD_PACKAGES[@]}")
for arg in "$@"; do
  case "$arg" in
    --with-tests) want+=("${TEST_PACKAGES[@]}") ;;
    --with-fuzz) want+=("${FUZZ_PACKAGES[@]}") ;;
  esac
done

missing=()
for p in "${want[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then missing+=("$p"); fi
done
if ((${#missing[@]} == 0)); then exit 0; fi

echo "Installing: ${missing[*]}"
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
