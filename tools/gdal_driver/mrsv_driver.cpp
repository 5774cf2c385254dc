// GDAL driver plugin for MRSV grid streams (issue 25), read-only: gdalinfo,
// gdal_translate, QGIS, rasterio, ... open .mrsv files when gdal_MRSV.so is
// in GDAL_DRIVER_PATH. The grid is decoded once at open; its georeferencing
// comes from the meta chunk (decision D73), and its overviews are the wavelet
// levels: overview k is the stream decoded k levels above the finest
// (spec 5.8.3), made when first asked for.
#include <gdal_pam.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <vector>

#include "io/gdal_georef.h"
#include "mrsv/grid.h"
#include "mrsv/grid_formats.h"
#include "mrsv/progressive_mesh.h"
#include "mrsv/progressive_tet_mesh.h"

namespace {

using FileBytes = std::shared_ptr<const std::vector<uint8_t>>;

class MrsvDataset;

class MrsvRasterBand final : public GDALPamRasterBand {
 public:
  MrsvRasterBand(MrsvDataset* ds, GDALDataType type);
  CPLErr IReadBlock(int block_x, int block_y, void* image) override;
  double GetNoDataValue(int* has) override;
  const char* GetUnitType() override;
  int GetOverviewCount() override;
  GDALRasterBand* GetOverview(int i) override;
};

class MrsvDataset final : public GDALPamDataset {
 public:
  static int Identify(GDALOpenInfo* info);
  static GDALDataset* Open(GDALOpenInfo* info);

  CPLErr GetGeoTransform(double* gt) override;
  const OGRSpatialReference* GetSpatialRef() const override { return srs_.IsEmpty() ? nullptr : &srs_; }

 private:
  friend class MrsvRasterBand;
  // The grid of `bytes` decoded `reduce` levels above the finest, or null
  // with a GDAL error naming `name`.
  static std::unique_ptr<MrsvDataset> decode(const char* name, FileBytes bytes, int reduce);
  MrsvDataset* overview(int i);

  std::string name_;
  FileBytes bytes_;
  mrsv::DecodedGrid grid_;
  mrsv::Metadata metadata_;  // with the spacing of this resolution
  int overview_count_ = 0;   // of the full-resolution dataset only
  std::vector<std::unique_ptr<MrsvDataset>> overviews_;
  OGRSpatialReference srs_;
};

MrsvRasterBand::MrsvRasterBand(MrsvDataset* ds, GDALDataType type) {
  poDS = ds;
  nBand = 1;
  eDataType = type;
  // Whole rows: the samples are in memory already, row after row.
  nBlockXSize = ds->GetRasterXSize();
  nBlockYSize = 1;
}

CPLErr MrsvRasterBand::IReadBlock(int, int block_y, void* image) {
  const auto* ds = static_cast<MrsvDataset*>(poDS);
  const size_t bytes = GDALGetDataTypeSizeBytes(eDataType);
  const size_t row = static_cast<size_t>(nBlockXSize) * bytes;
  std::memcpy(image, ds->grid_.samples.data() + static_cast<size_t>(block_y) * row, row);
#if !CPL_IS_LSB
  GDALSwapWords(image, static_cast<int>(bytes), nBlockXSize, static_cast<int>(bytes));  // stored little-endian
#endif
  return CE_None;
}

double MrsvRasterBand::GetNoDataValue(int* has) {
  const auto& header = static_cast<MrsvDataset*>(poDS)->grid_.header;
  if (has) *has = header.hasNodata();
  return header.hasNodata() ? mrsv::nodataValue(header.nodata_bits, header.sample_type) : 0;
}

const char* MrsvRasterBand::GetUnitType() {
  const std::string* units = static_cast<MrsvDataset*>(poDS)->metadata_.find("value_units");
  return units ? units->c_str() : "";
}

int MrsvRasterBand::GetOverviewCount() { return static_cast<MrsvDataset*>(poDS)->overview_count_; }

GDALRasterBand* MrsvRasterBand::GetOverview(int i) {
  MrsvDataset* o = static_cast<MrsvDataset*>(poDS)->overview(i);
  return o ? o->GetRasterBand(1) : nullptr;
}

int MrsvDataset::Identify(GDALOpenInfo* info) {
  static const uint8_t kSignature[9] = {0x8E, 'M', 'R', 'S', 'V', 0x0D, 0x0A, 0x1A, 0x0A};
  return info->nHeaderBytes >= 12 && std::memcmp(info->pabyHeader, kSignature, 9) == 0;
}

std::unique_ptr<MrsvDataset> MrsvDataset::decode(const char* name, FileBytes bytes, int reduce) {
  auto ds = std::make_unique<MrsvDataset>();
  mrsv::DecodeOptions options;
  options.reduce_levels = reduce;
  if (mrsv::Error e = mrsv::decodeGrid(bytes->data(), bytes->size(), options, &ds->grid_); !e.ok()) {
    CPLError(CE_Failure, CPLE_AppDefined, "%s: %s", name, e.describe().c_str());
    return nullptr;
  }
  const mrsv::GridHeader& h = ds->grid_.header;
  if (!ds->grid_.has_samples || h.num_dims > 2) {
    CPLError(CE_Failure, CPLE_OpenFailed, "%s: %s", name,
             h.num_dims > 2 ? "a 3-D grid is not a raster; decode it with mrsv decode"
                            : "the stream ends before its sample data");
    return nullptr;
  }
  ds->name_ = name;
  ds->bytes_ = std::move(bytes);
  ds->nRasterXSize = static_cast<int>(ds->grid_.output_size[0]);
  ds->nRasterYSize = static_cast<int>(ds->grid_.output_size[1]);
  ds->metadata_ = mrsv::reducedResolutionMetadata(ds->grid_.metadata, h, ds->grid_.wavelet.levels, reduce);
  if (const std::string* crs = ds->metadata_.find("crs")) {
    if (OGRSpatialReferenceH srs = mrsv::spatialRefFromCrs(*crs)) {
      ds->srs_ = *OGRSpatialReference::FromHandle(srs);
      ds->srs_.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
      OSRDestroySpatialReference(srs);
    }
  }
  const std::string* point = ds->metadata_.find("area_or_point");
  ds->SetMetadataItem(GDALMD_AREA_OR_POINT, point && *point == "point" ? GDALMD_AOP_POINT : GDALMD_AOP_AREA);
  ds->SetBand(1, new MrsvRasterBand(ds.get(), mrsv::gdalTypeOf(h.sample_type)));
  return ds;
}

GDALDataset* MrsvDataset::Open(GDALOpenInfo* info) {
  if (!Identify(info)) return nullptr;
  if (info->eAccess == GA_Update) {
    CPLError(CE_Failure, CPLE_NotSupported, "%s: the MRSV driver is read-only", info->pszFilename);
    return nullptr;
  }
  GByte* data = nullptr;
  vsi_l_offset size = 0;
  if (!VSIIngestFile(nullptr, info->pszFilename, &data, &size, -1)) return nullptr;
  auto bytes = std::make_shared<std::vector<uint8_t>>(data, data + size);
  VSIFree(data);
  if (mrsv::isProgressiveMeshStream(bytes->data(), bytes->size()) ||
      mrsv::isProgressiveTetStream(bytes->data(), bytes->size())) {
    CPLError(CE_Failure, CPLE_OpenFailed, "%s: a mesh stream, not a grid", info->pszFilename);
    return nullptr;
  }
  std::unique_ptr<MrsvDataset> ds = decode(info->pszFilename, bytes, 0);
  if (!ds) return nullptr;
  // One overview per wavelet level that reaches the decoded bands (a stream
  // coded by prediction alone, or a stored one, has none).
  const mrsv::DecodedGrid& g = ds->grid_;
  if (g.header.coding == mrsv::GridCoding::kWavelet)
    ds->overview_count_ = std::max(g.wavelet.levels[0], g.header.num_dims > 1 ? g.wavelet.levels[1] : uint8_t{0});
  ds->overviews_.resize(static_cast<size_t>(ds->overview_count_));
  ds->SetDescription(info->pszFilename);
  ds->TryLoadXML();
  return ds.release();
}

MrsvDataset* MrsvDataset::overview(int i) {
  if (i < 0 || i >= overview_count_) return nullptr;
  auto& slot = overviews_[static_cast<size_t>(i)];
  if (!slot) slot = decode(name_.c_str(), bytes_, i + 1);
  return slot.get();
}

CPLErr MrsvDataset::GetGeoTransform(double* gt) {
  return mrsv::geoTransformFromMetadata(metadata_, gt) ? CE_None : GDALPamDataset::GetGeoTransform(gt);
}

}  // namespace

extern "C" __attribute__((visibility("default"))) void GDALRegister_MRSV() {
  if (!GDAL_CHECK_VERSION("MRSV driver")) return;
  if (GDALGetDriverByName("MRSV") != nullptr) return;
  auto* driver = new GDALDriver();
  driver->SetDescription("MRSV");
  driver->SetMetadataItem(GDAL_DCAP_RASTER, "YES");
  driver->SetMetadataItem(GDAL_DMD_LONGNAME, "MRSV multiresolution grid (read-only)");
  driver->SetMetadataItem(GDAL_DMD_EXTENSION, "mrsv");
  driver->SetMetadataItem(GDAL_DCAP_VIRTUALIO, "YES");
  driver->pfnOpen = MrsvDataset::Open;
  driver->pfnIdentify = MrsvDataset::Identify;
  GetGDALDriverManager()->RegisterDriver(driver);
}
