// Rasters through GDAL (issue 25): any raster GDAL opens in, GeoTIFF out.
// Georeferencing follows decision D73: grid row 0 is the raster's first row,
// `origin` is the centre of pixel (0, 0), `spacing` the geotransform's signed
// pixel sizes (negative y for north-up rasters), `crs` EPSG:n or one-line WKT2.
#include "io/gdal_grid.h"

#include "io/gdal_dataset.h"
#include "io/gdal_georef.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include "io/number_list.h"
#include "mrsv/raw_grid.h"

namespace mrsv {
namespace {

void registerDrivers() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

// GDAL's own messages go to stderr by default; ours must be one line, so its
// errors are kept quiet while a call runs and its last message is quoted.
class QuietGdalErrors {
 public:
  QuietGdalErrors() {
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietGdalErrors() { CPLPopErrorHandler(); }
  QuietGdalErrors(const QuietGdalErrors&) = delete;
  QuietGdalErrors& operator=(const QuietGdalErrors&) = delete;

  // " (GDAL: message)" on one line, or "" when GDAL said nothing.
  static std::string last() {
    std::string m = CPLGetLastErrorMsg();
    for (char& c : m)
      if (c == '\n' || c == '\r') c = ' ';
    return m.empty() ? "" : " (GDAL: " + m + ")";
  }
};

bool hostIsLittleEndian() {
  const uint16_t one = 1;
  uint8_t first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

bool sampleTypeOf(GDALDataType type, SampleType* out) {
  switch (type) {
    case GDT_Byte: *out = SampleType::kUint8; return true;
    case GDT_Int16: *out = SampleType::kInt16; return true;
    case GDT_UInt16: *out = SampleType::kUint16; return true;
    case GDT_Int32: *out = SampleType::kInt32; return true;
    case GDT_Float32: *out = SampleType::kFloat32; return true;
    case GDT_Float64: *out = SampleType::kFloat64; return true;
    default: return false;
  }
}

// The band's no-data value as the sample type's bit pattern. A value the type
// cannot hold (e.g. -9999 on a uint8 band) marks no sample, so it is dropped.
bool nodataBits(double value, SampleType type, uint64_t* bits) {
  if (type == SampleType::kFloat64) {
    std::memcpy(bits, &value, 8);
    return true;
  }
  if (type == SampleType::kFloat32) {
    float f = static_cast<float>(value);
    if (!std::isnan(value) && static_cast<double>(f) != value) return false;
    uint32_t b;
    std::memcpy(&b, &f, 4);
    *bits = b;
    return true;
  }
  double lo = 0, hi = 0;
  switch (type) {
    case SampleType::kUint8: hi = 255; break;
    case SampleType::kInt16: lo = -32768; hi = 32767; break;
    case SampleType::kUint16: hi = 65535; break;
    default: lo = -2147483648.0; hi = 2147483647.0;
  }
  if (!(value >= lo && value <= hi) || value != std::floor(value)) return false;
  const uint64_t mask = (uint64_t{1} << (8 * sampleSize(type))) - 1;
  *bits = static_cast<uint64_t>(static_cast<int64_t>(value)) & mask;
  return true;
}

// crs: the EPSG code when GDAL identifies one, else WKT2 on one line.
std::string crsText(OGRSpatialReferenceH srs) {
  const char* authority = OSRGetAuthorityName(srs, nullptr);
  const char* code = OSRGetAuthorityCode(srs, nullptr);
  if (authority && code && std::strcmp(authority, "EPSG") == 0) return std::string("EPSG:") + code;
  char* wkt = nullptr;
  const char* options[] = {"FORMAT=WKT2_2018", "MULTILINE=NO", nullptr};
  std::string out;
  if (OSRExportToWktEx(srs, &wkt, options) == OGRERR_NONE && wkt) out = wkt;
  CPLFree(wkt);
  return out;
}

// Georeferencing of `ds` into `in->metadata` (D73).
bool readGeoreferencing(const std::string& path, GDALDatasetH ds, GridInput* in,
                        std::string* error) {
  double gt[6];
  if (GDALGetGeoTransform(ds, gt) == CE_None) {
    if (gt[2] != 0 || gt[4] != 0) {
      *error = path + ": rotated or sheared geotransform (row/column terms " + formatMetaNumber(gt[2]) +
               ", " + formatMetaNumber(gt[4]) +
               ") is not supported: MRSV grids are axis-aligned; warp it north-up first (gdalwarp)";
      return false;
    }
    // GDAL's geotransform is always the top-left corner of pixel (0, 0), for
    // PixelIsPoint GeoTIFFs too (GDAL shifts those by half a pixel on reading,
    // its RFC 33), so the sample's position is that corner plus half a pixel.
    const double origin[2] = {gt[0] + 0.5 * gt[1], gt[3] + 0.5 * gt[5]};
    if (!std::isfinite(origin[0]) || !std::isfinite(origin[1]) || gt[1] == 0 || gt[5] == 0) {
      *error = path + ": geotransform has a zero or non-finite pixel size or origin";
      return false;
    }
    in->metadata.set("origin", formatMetaNumberList({origin[0], origin[1]}));
    in->metadata.set("spacing", formatMetaNumberList({gt[1], gt[5]}));
  }
  OGRSpatialReferenceH srs = GDALGetSpatialRef(ds);
  if (srs) {  // null when the raster has no CRS
    std::string crs = crsText(srs);
    if (!crs.empty()) in->metadata.set("crs", crs);
    char* unit = nullptr;
    if (OSRIsProjected(srs)) OSRGetLinearUnits(srs, &unit);
    else if (OSRIsGeographic(srs)) OSRGetAngularUnits(srs, &unit);
    if (unit && *unit) in->metadata.set("spatial_units", unit);
  }
  // Kept so that a GeoTIFF written back says PixelIsPoint as its source did.
  const char* area_or_point = GDALGetMetadataItem(ds, GDALMD_AREA_OR_POINT, nullptr);
  if (area_or_point && std::strcmp(area_or_point, GDALMD_AOP_POINT) == 0)
    in->metadata.set("area_or_point", "point");
  return true;
}

}  // namespace

bool gdalAvailable() { return true; }

bool readGdalGrid(const std::string& path, int band, GridInput* in, std::string* error) {
  registerDrivers();
  QuietGdalErrors quiet;
  GDALDatasetH ds = GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
  if (!ds) {
    *error = path + ": not a raster GDAL reads" + QuietGdalErrors::last();
    return false;
  }
  const bool ok = readGdalDataset(ds, path, band, in, error);
  GDALClose(ds);
  return ok;
}

bool readGdalDataset(GDALDatasetH ds, const std::string& path, int band, GridInput* in,
                     std::string* error, GDALProgressFunc progress, void* progress_data) {
  const int bands = GDALGetRasterCount(ds);
  if (bands < 1) {
    *error = path + ": the raster has no band";
    return false;
  }
  if (band == 0 && bands > 1) {
    *error = path + ": " + std::to_string(bands) +
             " bands, and an MRSV grid holds one: choose one with --band N (1 to " +
             std::to_string(bands) + ")";
    return false;
  }
  if (band < 0 || band > bands) {
    *error = path + ": --band " + std::to_string(band) + " is not one of its bands 1 to " +
             std::to_string(bands);
    return false;
  }
  GDALRasterBandH b = GDALGetRasterBand(ds, band == 0 ? 1 : band);
  const GDALDataType type = GDALGetRasterDataType(b);
  // GDAL 3.6 has no Int8 type: signed bytes are Byte with this flag.
  const char* pixel_type = GDALGetMetadataItem(b, "PIXELTYPE", "IMAGE_STRUCTURE");
  if (!sampleTypeOf(type, &in->header.sample_type) ||
      (pixel_type && std::strcmp(pixel_type, "SIGNEDBYTE") == 0)) {
    *error = path + ": sample type " +
             (pixel_type && std::strcmp(pixel_type, "SIGNEDBYTE") == 0 ? "Int8" : GDALGetDataTypeName(type)) +
             " has no MRSV equivalent (Byte, Int16, UInt16, Int32, Float32, Float64); convert it "
             "with gdal_translate -ot";
    return false;
  }
  const int w = GDALGetRasterXSize(ds), h = GDALGetRasterYSize(ds);
  in->header.num_dims = 2;
  in->header.size_x = static_cast<uint32_t>(w);
  in->header.size_y = static_cast<uint32_t>(h);
  if (std::string problem = gridHeaderProblem(in->header); !problem.empty()) {
    *error = path + ": " + problem;
    return false;
  }
  if (!readGeoreferencing(path, ds, in, error)) return false;
  int has_nodata = 0;
  const double nodata = GDALGetRasterNoDataValue(b, &has_nodata);
  if (has_nodata && nodataBits(nodata, in->header.sample_type, &in->header.nodata_bits))
    in->header.grid_flags |= kGridFlagHasNodata;
  if (const char* units = GDALGetRasterUnitType(b); units && *units)
    in->metadata.set("value_units", units);

  const size_t bytes = sampleSize(in->header.sample_type);
  in->samples.resize(static_cast<size_t>(in->header.sampleCount()) * bytes);
  GDALRasterIOExtraArg extra;
  INIT_RASTERIO_EXTRA_ARG(extra);
  extra.pfnProgress = progress;
  extra.pProgressData = progress_data;
  if (GDALRasterIOEx(b, GF_Read, 0, 0, w, h, in->samples.data(), w, h, type, 0, 0, &extra) != CE_None) {
    *error = path + ": reading the samples failed" + QuietGdalErrors::last();
    return false;
  }
  // GDAL gives host byte order; grids hold little-endian samples.
  if (!hostIsLittleEndian()) swapSampleBytes(&in->samples, bytes);
  return true;
}

bool encodeGeoTiff(const std::string& path, const GridHeader& header, const Metadata& metadata,
                   const uint32_t size[3], const std::vector<uint8_t>& samples,
                   std::vector<uint8_t>* out, std::string* error) {
  if (header.num_dims > 2) {
    *error = path + ": GeoTIFF holds 1-D and 2-D grids; this one is 3-D: write .raw or .nrrd";
    return false;
  }
  registerDrivers();
  QuietGdalErrors quiet;
  GDALDriverH driver = GDALGetDriverByName("GTiff");
  if (!driver) {
    *error = path + ": this GDAL has no GTiff driver";
    return false;
  }
  // Written in GDAL's memory file system, then handed to the caller, which
  // writes it atomically: no half-written GeoTIFF ever appears at `path`.
  static int serial = 0;
  const std::string name = "/vsimem/mrsv_geotiff_" + std::to_string(++serial) + ".tif";
  const SampleType type = header.sample_type;
  const int w = static_cast<int>(size[0]), h = header.num_dims > 1 ? static_cast<int>(size[1]) : 1;
  const char* options[] = {"BIGTIFF=IF_SAFER", nullptr};
  GDALDatasetH ds = GDALCreate(driver, name.c_str(), w, h, 1, gdalTypeOf(type), const_cast<char**>(options));
  if (!ds) {
    *error = path + ": GDAL cannot create the GeoTIFF" + QuietGdalErrors::last();
    return false;
  }
  bool ok = true;
  GDALRasterBandH band = GDALGetRasterBand(ds, 1);
  double gt[6];
  if (geoTransformFromMetadata(metadata, gt)) ok = GDALSetGeoTransform(ds, gt) == CE_None;
  const std::string* point = metadata.find("area_or_point");
  if (ok && point && *point == "point")
    ok = GDALSetMetadataItem(ds, GDALMD_AREA_OR_POINT, GDALMD_AOP_POINT, nullptr) == CE_None;
  if (const std::string* crs = metadata.find("crs"); ok && crs) {
    if (OGRSpatialReferenceH srs = spatialRefFromCrs(*crs)) {
      ok = GDALSetSpatialRef(ds, srs) == CE_None;
      OSRDestroySpatialReference(srs);
    } else {
      std::fprintf(stderr, "mrsv: %s: note: crs '%.60s' is neither EPSG:n nor WKT that GDAL reads; "
                           "the GeoTIFF has no CRS\n", path.c_str(), crs->c_str());
    }
  }
  if (ok && header.hasNodata())
    ok = GDALSetRasterNoDataValue(band, nodataValue(header.nodata_bits, type)) == CE_None;
  if (const std::string* units = metadata.find("value_units"); ok && units)
    ok = GDALSetRasterUnitType(band, units->c_str()) == CE_None;
  if (ok) {
    std::vector<uint8_t> host = samples;  // GDAL takes host byte order
    if (!hostIsLittleEndian()) swapSampleBytes(&host, sampleSize(type));
    ok = GDALRasterIO(band, GF_Write, 0, 0, w, h, host.data(), w, h, gdalTypeOf(type), 0, 0) == CE_None;
  }
  std::string message = ok ? "" : QuietGdalErrors::last();
  // GDAL 3.6's GDALClose returns nothing: a failed flush shows as an error.
  if (ok) CPLErrorReset();
  GDALClose(ds);
  if (ok && CPLGetLastErrorType() >= CE_Failure) {
    ok = false;
    message = QuietGdalErrors::last();
  }
  if (ok) {
    vsi_l_offset length = 0;
    GByte* data = VSIGetMemFileBuffer(name.c_str(), &length, TRUE);
    if (data) out->assign(data, data + length);
    else ok = false;
    CPLFree(data);
  }
  VSIUnlink(name.c_str());
  if (!ok) *error = path + ": writing the GeoTIFF failed" + message;
  return ok;
}

}  // namespace mrsv
