// Builds without GDAL (MRSV_GDAL off): rasters that need it are refused with
// one line saying how to get a build that reads them.
#include "io/gdal_grid.h"

namespace mrsv {
namespace {

const char kNoGdal[] =
    ": this mrsv was built without GDAL (install libgdal-dev and configure with -DMRSV_GDAL=ON)";

}  // namespace

bool gdalAvailable() { return false; }

bool readGdalGrid(const std::string& path, int, GridInput*, std::string* error) {
  *error = path + kNoGdal;
  return false;
}

bool encodeGeoTiff(const std::string& path, const GridHeader&, const Metadata&, const uint32_t[3],
                   const std::vector<uint8_t>&, std::vector<uint8_t>*, std::string* error) {
  *error = path + kNoGdal;
  return false;
}

}  // namespace mrsv
