// A grid from a raster GDAL already has open: what readGdalGrid (gdal_grid.h)
// does after opening the file, shared with the driver plugin's CreateCopy
// (tools/gdal_driver), so that `gdal_translate -of MRSV` and `mrsv encode`
// map a raster to a grid the same way (decision D73).
#pragma once

#include <gdal.h>

#include <string>

#include "mrsv/grid_formats.h"

namespace mrsv {

// Reads band `band` (1-based; 0: the only band) of `ds` into `in`: samples in
// file order, georeferencing, no-data value and units (D73). `name` stands
// for the raster in errors. `progress` (may be null) follows the sample read.
// One line in `error` on failure.
bool readGdalDataset(GDALDatasetH ds, const std::string& name, int band, GridInput* in,
                     std::string* error, GDALProgressFunc progress = nullptr,
                     void* progress_data = nullptr);

}  // namespace mrsv
