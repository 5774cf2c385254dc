// The meta chunk's georeferencing as GDAL wants it (decision D73).
#include "io/gdal_georef.h"

#include <cstdlib>
#include <cstring>
#include <vector>

#include "io/number_list.h"
#include "mrsv/raw_grid.h"

namespace mrsv {

GDALDataType gdalTypeOf(SampleType type) {
  switch (type) {
    case SampleType::kUint8: return GDT_Byte;
    case SampleType::kInt16: return GDT_Int16;
    case SampleType::kUint16: return GDT_UInt16;
    case SampleType::kInt32: return GDT_Int32;
    case SampleType::kFloat32: return GDT_Float32;
    case SampleType::kFloat64: return GDT_Float64;
  }
  return GDT_Unknown;
}

double nodataValue(uint64_t bits, SampleType type) {
  uint8_t bytes[8];
  for (int k = 0; k < 8; ++k) bytes[k] = static_cast<uint8_t>(bits >> (8 * k));  // little-endian
  return sampleValue(bytes, type);
}

bool geoTransformFromMetadata(const Metadata& metadata, double gt[6]) {
  std::vector<double> origin, spacing;
  const std::string* o = metadata.find("origin");
  const std::string* s = metadata.find("spacing");
  if (!o || !s || !parseMetaNumberList(*o, &origin) || !parseMetaNumberList(*s, &spacing) ||
      origin.size() < 2 || spacing.size() < 2 || spacing[0] == 0 || spacing[1] == 0)
    return false;
  const double out[6] = {origin[0] - 0.5 * spacing[0], spacing[0], 0,
                         origin[1] - 0.5 * spacing[1], 0, spacing[1]};
  std::memcpy(gt, out, sizeof out);
  return true;
}

OGRSpatialReferenceH spatialRefFromCrs(const std::string& crs) {
  OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
  OGRErr e = OGRERR_FAILURE;
  if (crs.compare(0, 5, "EPSG:") == 0 && crs.size() > 5 && crs.size() < 15 &&
      crs.find_first_not_of("0123456789", 5) == std::string::npos) {
    e = OSRImportFromEPSG(srs, std::atoi(crs.c_str() + 5));
  } else {
    std::string wkt = crs;
    char* text = wkt.data();
    e = OSRImportFromWkt(srs, &text);
  }
  if (e != OGRERR_NONE) {
    OSRDestroySpatialReference(srs);
    return nullptr;
  }
  // origin and spacing are x (easting, longitude) first, whatever the CRS says.
  OSRSetAxisMappingStrategy(srs, OAMS_TRADITIONAL_GIS_ORDER);
  return srs;
}

}  // namespace mrsv
