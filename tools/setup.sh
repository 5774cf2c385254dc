#!/usr/bin/env bash
# Set-up for MRSV on Debian 12: installs the Debian packages the project needs
# when they are missing, then configures and builds the Release tree in build/.
# As root it runs apt-get itself; otherwise it prints the one line to run and stops.
# Both README commands start with this step.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

packages=(
  g++ cmake ninja-build pkg-config          # toolchain
  libeigen3-dev libcgal-dev libtet1.5-dev   # linear algebra, geometry, tetrahedralisation
  libgtest-dev libgmock-dev libbenchmark-dev  # tests and benchmarks
  clang libclang-rt-14-dev                  # libFuzzer and the sanitizer runtimes
  zstd libzstd-dev                          # the ../shared/data files are zstd frames
  python3                                   # conformance runner and vector generator
  python3-vtk9 python3-meshio               # the real clients of our .vtu/.vtk files (tet_clients_test)
  python3-matplotlib                        # the section 7 pictures (tools/experiments, experiments_section7_quick)
  python3-pybind11 python3-numpy python3-pytest  # the Python module (python/) and its tests
  libgdal-dev gdal-bin python3-gdal        # GeoTIFF and other rasters (MRSV_GDAL); gdalinfo, gdal_translate in the tests
  python3-rasterio                         # the GDAL driver plugin's test through rasterio
  libhdf5-dev python3-h5py hdf5-tools     # the HDF5 filter plugin (MRSV_HDF5), its h5py test, h5dump
  hdf5-filter-plugin-zfp-serial hdf5-filter-plugin  # ZFP, LZ4, BZip2 HDF5 filters: peers in tools/bench/hdf5_bench.py
  libhdf5-openmpi-dev openmpi-bin          # parallel HDF5 for hdf5_filter_mpi_test (beside libhdf5-dev: the plugin
                                           # for h5py still builds against the serial HDF5, found through h5cc)
  libopenmpi-dev openmpi-bin                # mrsv-mpi (MRSV_MPI): tiled grids coded by MPI ranks, mpi_tests
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" -eq 0 ]; then
    echo "setup: installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  else
    echo "setup: missing Debian packages. Run this, then try again:" >&2
    echo "  sudo apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
fi

if [ ! -d "$root/../shared/data" ]; then
  echo "setup: warning: ../shared/data is not beside the project; the tests on real data will fail" >&2
fi

generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if [ ! -f "$root/build/CMakeCache.txt" ]; then
  # MRSV_BENCHMARKS=OFF in the environment leaves tools/bench's benchmarks out of the
  # default build (.ci/run does: no test runs them).
  cmake -S "$root" -B "$root/build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
    -DMRSV_BENCHMARKS="${MRSV_BENCHMARKS:-ON}" >/dev/null
fi
echo "setup: building (Release) in build/"
log=$(mktemp)
if ! cmake --build "$root/build" -j "$(nproc)" >"$log" 2>&1; then
  grep -E "error|Error" "$log" | head -40 >&2
  rm -f "$log"
  echo "setup: the build failed" >&2
  exit 1
fi
rm -f "$log"
