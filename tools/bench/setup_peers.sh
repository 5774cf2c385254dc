#!/usr/bin/env bash
# Installs the peer codecs and the Python packages that tools/bench/rd_bench.py needs,
# the mesh peers of tools/bench/mesh_bench.py: meshoptimizer (headers and CMake
# config, for build/mesh_peers; re-run cmake after installing it) and Draco's tools
# (Debian 12 packages), and the terrain meshers of tools/bench/terrain_mesh_bench:
# node (Debian) with the npm packages delatin and @mapbox/martini, installed into
# build/node_peers. As root it runs apt-get for whatever is missing; otherwise it
# prints the apt-get line to run and exits 1. Exit 0 when everything is present.
#
#   tools/bench/setup_peers.sh
set -euo pipefail

# package -> a file that shows it is installed
declare -A probe=(
  [zfp]=/usr/bin/zfp
  [libopenjp2-tools]=/usr/bin/opj_compress
  [libjxl-tools]=/usr/bin/cjxl
  [xz-utils]=/usr/bin/xz
  [zstd]=/usr/bin/zstd
  [python3-numpy]=/usr/lib/python3/dist-packages/numpy/__init__.py
  [python3-matplotlib]=/usr/lib/python3/dist-packages/matplotlib/__init__.py
  [libmeshoptimizer-dev]=/usr/include/meshoptimizer.h
  [draco]=/usr/bin/draco_encoder
)
order=(zfp libopenjp2-tools libjxl-tools xz-utils zstd python3-numpy python3-matplotlib
       libmeshoptimizer-dev draco)
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)

# The npm peers, pinned (the registry is the only network the set-up uses).
node_peers() {
  local dir=$root/build/node_peers
  if [ -f "$dir/node_modules/delatin/package.json" ] && [ -f "$dir/node_modules/@mapbox/martini/package.json" ]; then
    return 0
  fi
  echo "setup_peers: npm install delatin@0.2.0 @mapbox/martini@0.2.0 into build/node_peers"
  mkdir -p "$dir"
  npm install --prefix "$dir" --no-audit --no-fund --silent delatin@0.2.0 @mapbox/martini@0.2.0
}

missing=()
# node and npm: Debian's nodejs and npm, or any node that brings its own npm.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then missing+=(nodejs npm); fi
for p in "${order[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
     [ ! -e "${probe[$p]}" ]; then
    missing+=("$p")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  node_peers
  echo "setup_peers: all peer packages present (${order[*]}; npm: delatin, @mapbox/martini)"
  exit 0
fi

line="apt-get install -y --no-install-recommends ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then
  echo "setup_peers: missing: ${missing[*]}" >&2
  echo "setup_peers: run as root:  apt-get update && $line" >&2
  exit 1
fi

echo "setup_peers: installing: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -q
$line
node_peers
echo "setup_peers: done"
