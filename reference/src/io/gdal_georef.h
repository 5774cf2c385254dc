// The meta chunk's georeferencing as GDAL wants it (decision D73), shared by
// the GeoTIFF writer (gdal_grid.cpp) and the GDAL driver plugin (gdal_driver/).
#pragma once

#include <gdal.h>
#include <ogr_srs_api.h>

#include <cstdint>
#include <string>

#include "mrsv/grid.h"
#include "mrsv/metadata.h"

namespace mrsv {

GDALDataType gdalTypeOf(SampleType type);

// The no-data bit pattern of the grid header as the double GDAL takes.
double nodataValue(uint64_t bits, SampleType type);

// The geotransform of `origin` and `spacing` (at least two numbers each,
// nonzero spacing): the corner of pixel (0, 0) is half a pixel before the
// sample. False when the entries are missing or unusable.
bool geoTransformFromMetadata(const Metadata& metadata, double gt[6]);

// A spatial reference from a `crs` value, or null (the caller destroys it).
// Only the two forms D73 writes, EPSG:n and WKT: the value comes from a
// stream, and GDAL's general parser would also open files and URLs.
OGRSpatialReferenceH spatialRefFromCrs(const std::string& crs);

}  // namespace mrsv
