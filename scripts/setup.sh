#!/usr/bin/env bash
# setup.sh - installs brdfbench's dependencies from Debian 12's packages (idempotent: a
# package already installed is not fetched again) and configures + builds into build/.
# Run as root, or as a user with sudo.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config git python3 python3-jsonschema
  pocl-opencl-icd ocl-icd-opencl-dev ocl-icd-libopencl1 opencl-headers clinfo mesa-opencl-icd
  libopencv-dev libgsl-dev libjansson-dev
  glmark2-data povray-examples
  clang libclang-rt-14-dev
  libtcc-dev
  glslang-dev
  libsqlite3-dev libbenchmark-tools python3-scipy python3-yaml
)
as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  as_root apt-get update -qq
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# Some Debian images exclude /usr/share/doc from installs (dpkg path-exclude): the teapot's
# patch file then is missing although povray-examples is installed. Take it out of the
# package itself.
teapot=/usr/share/doc/povray/examples/advanced/teapot/teapot.inc
if [ ! -f "$teapot" ]; then
  echo "setup: $teapot is missing; extracting it from povray-examples" >&2
  tmp=$(mktemp -d)
  (cd "$tmp" && apt-get download povray-examples >/dev/null && dpkg-deb -x povray-examples_*.deb x)
  as_root mkdir -p "$(dirname "$teapot")"
  as_root cp "$tmp/x$teapot" "$teapot"
  rm -rf "$tmp"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j"$(nproc)"
