// GDAL driver plugin for MRSV grid streams (issue 25): gdalinfo,
// gdal_translate (both ways), QGIS, rasterio, ... open and write .mrsv files
// when gdal_MRSV.so is in GDAL_DRIVER_PATH. Opening reads the headers and the
// meta chunk only (georeferencing: decision D73); a resolution is decoded
// when its samples are first read. The overviews are the wavelet levels:
// overview k is the stream decoded k levels above the finest (spec 5.8.3),
// from the prefix of the stream that holds the bands it needs.
#include "mrsv_driver.h"

#include <gdal_pam.h>
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

// What every resolution of one file shares: its bytes and its headers.
struct Stream {
  std::string name;
  std::vector<uint8_t> bytes;
  mrsv::GridHeader header;
  mrsv::WaveletHeader wavelet;
  mrsv::Metadata metadata;
  std::vector<uint64_t> band_offsets;  // of the GBND chunks, in stream order
};

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
  // The dataset of `stream` `reduce` levels above the finest, of `size`; its
  // decode reads the first `prefix` bytes.
  MrsvDataset(std::shared_ptr<const Stream> stream, int reduce, const uint32_t size[2], size_t prefix);
  MrsvDataset* overview(int i);
  // The samples of this resolution, decoded on first use; false (with a GDAL
  // error naming the file, once) when the stream cannot be decoded.
  bool decode();

  std::shared_ptr<const Stream> stream_;
  int reduce_ = 0;
  size_t prefix_ = 0;
  bool decoded_ = false, failed_ = false;
  std::vector<uint8_t> samples_;
  mrsv::Metadata metadata_;  // with the spacing of this resolution
  int overview_count_ = 0;   // of the full-resolution dataset only
  std::vector<std::unique_ptr<MrsvDataset>> overviews_;
  OGRSpatialReference srs_;
};

MrsvRasterBand::MrsvRasterBand(MrsvDataset* ds, GDALDataType type) {
  poDS = ds;
  nBand = 1;
  eDataType = type;
  // Whole rows: the samples are in memory once decoded, row after row.
  nBlockXSize = ds->GetRasterXSize();
  nBlockYSize = 1;
}

CPLErr MrsvRasterBand::IReadBlock(int, int block_y, void* image) {
  auto* ds = static_cast<MrsvDataset*>(poDS);
  if (!ds->decode()) return CE_Failure;
  const size_t bytes = GDALGetDataTypeSizeBytes(eDataType);
  const size_t row = static_cast<size_t>(nBlockXSize) * bytes;
  std::memcpy(image, ds->samples_.data() + static_cast<size_t>(block_y) * row, row);
#if !CPL_IS_LSB
  GDALSwapWords(image, static_cast<int>(bytes), nBlockXSize, static_cast<int>(bytes));  // stored little-endian
#endif
  return CE_None;
}

double MrsvRasterBand::GetNoDataValue(int* has) {
  const mrsv::GridHeader& header = static_cast<MrsvDataset*>(poDS)->stream_->header;
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

MrsvDataset::MrsvDataset(std::shared_ptr<const Stream> stream, int reduce, const uint32_t size[2],
                         size_t prefix)
    : stream_(std::move(stream)), reduce_(reduce), prefix_(prefix) {
  nRasterXSize = static_cast<int>(size[0]);
  nRasterYSize = static_cast<int>(size[1]);
  const mrsv::GridHeader& h = stream_->header;
  metadata_ = mrsv::reducedResolutionMetadata(stream_->metadata, h, stream_->wavelet.levels, reduce);
  if (const std::string* crs = metadata_.find("crs")) {
    if (OGRSpatialReferenceH srs = mrsv::spatialRefFromCrs(*crs)) {
      srs_ = *OGRSpatialReference::FromHandle(srs);
      srs_.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
      OSRDestroySpatialReference(srs);
    }
  }
  const std::string* point = metadata_.find("area_or_point");
  SetMetadataItem(GDALMD_AREA_OR_POINT, point && *point == "point" ? GDALMD_AOP_POINT : GDALMD_AOP_AREA);
  SetBand(1, new MrsvRasterBand(this, mrsv::gdalTypeOf(h.sample_type)));
}

bool MrsvDataset::decode() {
  if (decoded_) return true;
  if (failed_) return false;  // said once already
  mrsv::DecodeOptions options;
  options.reduce_levels = reduce_;
  mrsv::DecodedGrid grid;
  mrsv::Error e = mrsv::decodeGrid(stream_->bytes.data(), prefix_, options, &grid);
  const char* problem = !e.ok() ? nullptr
                        : !grid.has_samples ? "the stream ends before its sample data"
                        : static_cast<int>(grid.output_size[0]) != nRasterXSize ||
                                  static_cast<int>(grid.output_size[1]) != nRasterYSize
                            ? "the decoded size differs from the one the headers gave"
                            : nullptr;
  if (!e.ok() || problem) {
    CPLError(CE_Failure, CPLE_AppDefined, "%s: %s", stream_->name.c_str(),
             problem ? problem : e.describe().c_str());
    failed_ = true;
    return false;
  }
  samples_ = std::move(grid.samples);
  decoded_ = true;
  return true;
}

GDALDataset* MrsvDataset::Open(GDALOpenInfo* info) {
  if (!Identify(info)) return nullptr;
  const char* name = info->pszFilename;
  if (info->eAccess == GA_Update) {
    CPLError(CE_Failure, CPLE_NotSupported, "%s: MRSV files are opened read-only (write one with CreateCopy)", name);
    return nullptr;
  }
  auto stream = std::make_shared<Stream>();
  stream->name = name;
  GByte* data = nullptr;
  vsi_l_offset size = 0;
  if (!VSIIngestFile(nullptr, name, &data, &size, -1)) return nullptr;
  stream->bytes.assign(data, data + size);
  VSIFree(data);
  const std::vector<uint8_t>& bytes = stream->bytes;
  if (mrsv::isProgressiveMeshStream(bytes.data(), bytes.size()) ||
      mrsv::isProgressiveTetStream(bytes.data(), bytes.size())) {
    CPLError(CE_Failure, CPLE_OpenFailed, "%s: a mesh stream, not a grid", name);
    return nullptr;
  }
  // The framing and checksums of the whole file (cheap beside decoding);
  // then the headers, meta chunk and no-data mask: the prefix before the
  // first band or stored samples, decoded.
  mrsv::Container container;
  mrsv::Error e = mrsv::readContainer(bytes.data(), bytes.size(), mrsv::ContainerOptions{}, &container);
  size_t samples_offset = bytes.size();
  bool has_samples = false;
  for (const mrsv::ChunkView& chunk : container.chunks) {
    const bool band = chunk.chunk_type == mrsv::kChunkBand;
    if (band) stream->band_offsets.push_back(chunk.offset);
    if ((band || chunk.chunk_type == mrsv::kChunkGridStored) && !has_samples) {
      samples_offset = chunk.offset;
      has_samples = true;
    }
  }
  mrsv::DecodedGrid grid;
  if (e.ok()) e = mrsv::decodeGrid(bytes.data(), samples_offset, mrsv::DecodeOptions{}, &grid);
  if (!e.ok()) {
    CPLError(CE_Failure, CPLE_OpenFailed, "%s: %s", name, e.describe().c_str());
    return nullptr;
  }
  const mrsv::GridHeader& h = grid.header;
  if (!has_samples || h.num_dims > 2) {
    CPLError(CE_Failure, CPLE_OpenFailed, "%s: %s", name,
             h.num_dims > 2 ? "a 3-D grid is not a raster; decode it with mrsv decode"
                            : "the stream ends before its sample data");
    return nullptr;
  }
  stream->header = h;
  stream->wavelet = grid.wavelet;
  stream->metadata = std::move(grid.metadata);
  const uint32_t full[2] = {h.size_x, h.num_dims > 1 ? h.size_y : 1};
  std::unique_ptr<MrsvDataset> ds(new MrsvDataset(stream, 0, full, bytes.size()));
  // One overview per wavelet level that reaches the decoded bands (a stream
  // coded by prediction alone, or a stored one, has none).
  if (h.coding == mrsv::GridCoding::kWavelet)
    ds->overview_count_ = std::max(grid.wavelet.levels[0], h.num_dims > 1 ? grid.wavelet.levels[1] : uint8_t{0});
  ds->overviews_.resize(static_cast<size_t>(ds->overview_count_));
  ds->SetDescription(name);
  ds->TryLoadXML();
  return ds.release();
}

MrsvDataset* MrsvDataset::overview(int i) {
  if (i < 0 || i >= overview_count_) return nullptr;
  auto& slot = overviews_[static_cast<size_t>(i)];
  if (!slot) {
    mrsv::ReducedResolution r;
    if (!mrsv::reducedResolution(stream_->header, stream_->wavelet, i + 1, &r)) return nullptr;
    // The bands the synthesis uses; a decode of the stream up to the next
    // band gives the same samples (spec 5.8.3) without reading the finer ones.
    const std::vector<uint64_t>& bands = stream_->band_offsets;
    const size_t prefix = r.bands_needed < bands.size() ? bands[r.bands_needed] : stream_->bytes.size();
    slot.reset(new MrsvDataset(stream_, i + 1, r.size, prefix));
  }
  return slot.get();
}

CPLErr MrsvDataset::GetGeoTransform(double* gt) {
  return mrsv::geoTransformFromMetadata(metadata_, gt) ? CE_None : GDALPamDataset::GetGeoTransform(gt);
}

}  // namespace

GDALDataset* mrsvOpen(GDALOpenInfo* info) { return MrsvDataset::Open(info); }

extern "C" __attribute__((visibility("default"))) void GDALRegister_MRSV() {
  if (!GDAL_CHECK_VERSION("MRSV driver")) return;
  if (GDALGetDriverByName("MRSV") != nullptr) return;
  auto* driver = new GDALDriver();
  driver->SetDescription("MRSV");
  driver->SetMetadataItem(GDAL_DCAP_RASTER, "YES");
  driver->SetMetadataItem(GDAL_DMD_LONGNAME, "MRSV multiresolution grid");
  driver->SetMetadataItem(GDAL_DMD_EXTENSION, "mrsv");
  driver->SetMetadataItem(GDAL_DCAP_VIRTUALIO, "YES");
  driver->SetMetadataItem(GDAL_DCAP_CREATECOPY, "YES");
  driver->SetMetadataItem(GDAL_DMD_CREATIONDATATYPES, "Byte Int16 UInt16 Int32 Float32 Float64");
  driver->SetMetadataItem(GDAL_DMD_CREATIONOPTIONLIST, kMrsvCreationOptionList);
  driver->pfnOpen = MrsvDataset::Open;
  driver->pfnIdentify = MrsvDataset::Identify;
  driver->pfnCreateCopy = mrsvCreateCopy;
  GetGDALDriverManager()->RegisterDriver(driver);
}
