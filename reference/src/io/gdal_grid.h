// Rasters through GDAL (issue 25), for grid_formats.cpp: gdal_grid.cpp in
// builds with GDAL, gdal_none.cpp (which refuses with a one-line error) without.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/grid.h"
#include "mrsv/grid_formats.h"
#include "mrsv/metadata.h"

namespace mrsv {

bool gdalAvailable();

// Reads band `band` (1-based; 0: the only band) of any raster GDAL opens:
// samples in file order (row 0 first), georeferencing and no-data into
// `in` as decision D73 says. One line in `error` on failure.
bool readGdalGrid(const std::string& path, int band, GridInput* in, std::string* error);

// The bytes of a one-band GeoTIFF of the 1-D or 2-D grid `samples` of
// `size`, georeferenced from `metadata` (D73), with the header's no-data value.
bool encodeGeoTiff(const std::string& path, const GridHeader& header, const Metadata& metadata,
                   const uint32_t size[3], const std::vector<uint8_t>& samples,
                   std::vector<uint8_t>* out, std::string* error);

}  // namespace mrsv
