// GDAL driver plugin for MRSV grid streams (issue 25): gdalinfo,
// gdal_translate (both ways), QGIS, rasterio, ... open and write .mrsv files
// when gdal_MRSV.so is in GDAL_DRIVER_PATH. Opening reads the headers and the
// meta chunk only (georeferencing: decision D73); a resolution is decoded
// when its samples are first read. The overviews are the wavelet levels:
// overview k is the stream decoded k levels above the finest (spec 5.8.3),
// from the prefix of the stream that holds the bands it needs.
// A tiled grid (spec 11) is not read whole: opening reads its header part,
// and each GDAL block is one tile, decoded by region decoding (11.5) from
// the byte ranges of that tile only; overview k is the grid reduced by k
// levels (11.6), one block per tile. A wavelet-coded grid in precincts
// (5.7.6) is read the same way, a block of 2^P positions at a time from the
// blocks that reach it: at full resolution and, for the 9/7 wavelet, at the
// overviews whose size is the lattice's; other overviews come from prefixes.
#include "mrsv_driver.h"

#include <gdal_pam.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <thread>
#include <vector>

#include "io/gdal_georef.h"
#include "mrsv/grid.h"
#include "mrsv/grid_formats.h"
#include "mrsv/progressive_mesh.h"
#include "mrsv/progressive_tet_mesh.h"
#include "mrsv/tiled_grid.h"

namespace {

// A file read through GDAL's virtual file layer, by offset (tiled grids).
class VsiByteSource final : public mrsv::ByteSource {
 public:
  VsiByteSource(VSILFILE* file, uint64_t size) : file_(file), size_(size) {}
  ~VsiByteSource() override { VSIFCloseL(file_); }
  uint64_t size() const override { return size_; }

 protected:
  bool readAt(uint64_t offset, size_t n, uint8_t* out) override {
    return VSIFSeekL(file_, offset, SEEK_SET) == 0 && VSIFReadL(out, 1, n, file_) == n;
  }

 private:
  VSILFILE* file_;
  uint64_t size_;
};

// What every resolution of one file shares: where its bytes are read, the
// prefix of them read so far, and its headers.
struct Stream {
  std::string name;
  std::unique_ptr<mrsv::ByteSource> source;
  std::vector<uint8_t> bytes;      // the first bytes.size() bytes of the file (not tiled grids)
  bool tiled = false;
  uint32_t tile_size[2] = {0, 0};  // tiled grids only
  uint32_t precinct = 0;           // grids in precincts (spec 5.7.6): samples per precinct side
  // The resolutions of a grid in precincts read by window: the full one and,
  // for the 9/7 wavelet, the overviews up to the fewest levels of an axis
  // (there the overview's size is the 2^K lattice's, spec 5.8.3 and 11.6).
  int precinct_levels = 0;

  // Reads the file up to `end` (at most its size); false, with a GDAL error
  // naming the file, on a read error.
  bool ensure(uint64_t end) {
    end = std::min<uint64_t>(end, source->size());
    if (end <= bytes.size()) return true;
    const size_t have = bytes.size();
    bytes.resize(end);
    if (source->read(have, end - have, bytes.data() + have)) return true;
    bytes.resize(have);
    CPLError(CE_Failure, CPLE_FileIO, "%s: cannot read it", name.c_str());
    return false;
  }
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
  // Tiled grids (and grids in precincts): a read of more than one block is one
  // region decode, tiles decoded by all cores (spec 11.5), instead of a decode
  // per block.
  CPLErr IRasterIO(GDALRWFlag rw, int x, int y, int x_size, int y_size, void* buffer, int buffer_x, int buffer_y,
                   GDALDataType buffer_type, GSpacing pixel_space, GSpacing line_space,
                   GDALRasterIOExtraArg* extra) override;
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
  // Opens a tiled grid by its header part only (spec 11.5): the headers, meta
  // chunk and tile index, through a one-sample region decode that also checks
  // them. Null, with a GDAL error, when the stream is broken.
  static std::unique_ptr<MrsvDataset> openTiled(const char* name, std::shared_ptr<Stream> stream);
  // The dataset of `stream` `reduce` levels above the finest, of `size`; its
  // decode reads the first `prefix` bytes.
  MrsvDataset(std::shared_ptr<Stream> stream, int reduce, const uint32_t size[2], size_t prefix);
  MrsvDataset* overview(int i);
  // The samples of this resolution, decoded on first use; false (with a GDAL
  // error naming the file, once) when the stream cannot be decoded.
  bool decode();
  // Tiled grids, and grids in precincts (byWindow()):
  // the window of this resolution's positions [x, x + x_size) x
  // [y, y + y_size) by region decode (spec 11.5, 11.6) on `threads` threads,
  // samples in host order; false, with a GDAL error naming the file and the
  // window, when the stream cannot give it.
  bool decodeWindow(int x, int y, int x_size, int y_size, int threads, mrsv::DecodedGrid* grid);
  // The same: block (x, y), one tile or precinct of this resolution.
  CPLErr readTile(int block_x, int block_y, void* image);
  bool tiled() const { return stream_->tiled; }
  bool byWindow() const { return stream_->tiled || (stream_->precinct > 0 && reduce_ <= stream_->precinct_levels); }

  std::shared_ptr<Stream> stream_;
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
  if (ds->tiled()) {
    // A block per tile: tile_size / 2^K positions of the reduced lattice.
    nBlockXSize = static_cast<int>(std::max<uint32_t>(1, ds->stream_->tile_size[0] >> ds->reduce_));
    nBlockYSize = static_cast<int>(std::max<uint32_t>(1, ds->stream_->tile_size[1] >> ds->reduce_));
    return;
  }
  if (ds->byWindow()) {  // a block per precinct
    nBlockXSize = static_cast<int>(std::min<uint32_t>(ds->stream_->precinct, ds->GetRasterXSize()));
    nBlockYSize = static_cast<int>(std::min<uint32_t>(ds->stream_->precinct, ds->GetRasterYSize()));
    return;
  }
  // Whole rows: the samples are in memory once decoded, row after row.
  nBlockXSize = ds->GetRasterXSize();
  nBlockYSize = 1;
}

CPLErr MrsvRasterBand::IReadBlock(int block_x, int block_y, void* image) {
  auto* ds = static_cast<MrsvDataset*>(poDS);
  if (ds->byWindow()) return ds->readTile(block_x, block_y, image);
  if (!ds->decode()) return CE_Failure;
  const size_t bytes = GDALGetDataTypeSizeBytes(eDataType);
  const size_t row = static_cast<size_t>(nBlockXSize) * bytes;
  std::memcpy(image, ds->samples_.data() + static_cast<size_t>(block_y) * row, row);
#if !CPL_IS_LSB
  GDALSwapWords(image, static_cast<int>(bytes), nBlockXSize, static_cast<int>(bytes));  // stored little-endian
#endif
  return CE_None;
}

CPLErr MrsvRasterBand::IRasterIO(GDALRWFlag rw, int x, int y, int x_size, int y_size, void* buffer, int buffer_x,
                                 int buffer_y, GDALDataType buffer_type, GSpacing pixel_space, GSpacing line_space,
                                 GDALRasterIOExtraArg* extra) {
  auto* ds = static_cast<MrsvDataset*>(poDS);
  const bool one_block = x / nBlockXSize == (x + x_size - 1) / nBlockXSize &&
                         y / nBlockYSize == (y + y_size - 1) / nBlockYSize;
  if (rw != GF_Read || !ds->byWindow() || one_block || x_size != buffer_x || y_size != buffer_y)
    return GDALPamRasterBand::IRasterIO(rw, x, y, x_size, y_size, buffer, buffer_x, buffer_y, buffer_type,
                                        pixel_space, line_space, extra);
  mrsv::DecodedGrid grid;
  if (!ds->decodeWindow(x, y, x_size, y_size, static_cast<int>(std::max(1u, std::thread::hardware_concurrency())),
                        &grid))
    return CE_Failure;
  const int bytes = GDALGetDataTypeSizeBytes(eDataType);
  for (int row = 0; row < y_size; ++row)
    GDALCopyWords(grid.samples.data() + static_cast<size_t>(row) * x_size * bytes, eDataType, bytes,
                  static_cast<uint8_t*>(buffer) + row * line_space, buffer_type, static_cast<int>(pixel_space), x_size);
  if (extra && extra->pfnProgress) extra->pfnProgress(1.0, "", extra->pProgressData);
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

MrsvDataset::MrsvDataset(std::shared_ptr<Stream> stream, int reduce, const uint32_t size[2],
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
  // Safe: GDAL calls a dataset's blocks from one thread at a time, and the
  // overviews are the same dataset's.
  if (!stream_->ensure(prefix_)) {
    failed_ = true;
    return false;
  }
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

bool MrsvDataset::decodeWindow(int x, int y, int x_size, int y_size, int threads, mrsv::DecodedGrid* grid) {
  if (failed_) return false;  // said once already
  // The window's positions on this resolution's 2^K lattice (spec 11.6) as
  // a box of full-resolution samples.
  const mrsv::GridHeader& h = stream_->header;
  const int k = reduce_;
  mrsv::GridRegion region;
  region.lo[0] = static_cast<uint32_t>(x) << k;
  region.lo[1] = static_cast<uint32_t>(y) << k;
  region.hi[0] = std::min<uint32_t>(h.size_x, (static_cast<uint32_t>(x + x_size - 1) << k) + 1);
  region.hi[1] = std::min<uint32_t>(h.num_dims > 1 ? h.size_y : 1, (static_cast<uint32_t>(y + y_size - 1) << k) + 1);
  mrsv::DecodeOptions options;
  options.reduce_levels = k;
  options.threads = threads;
  mrsv::Error e = mrsv::decodeGridRegion(*stream_->source, region, options, grid);
  const char* problem = !e.ok() ? nullptr
                        : !grid->has_samples ? "the stream ends before the window's samples"
                        : static_cast<int>(grid->output_size[0]) != x_size ||
                                  static_cast<int>(grid->output_size[1]) != y_size
                            ? "the window decoded to another size"
                            : nullptr;
  if (!e.ok() || problem) {
    CPLError(CE_Failure, CPLE_AppDefined, "%s: window %d,%d %dx%d: %s", stream_->name.c_str(), x, y, x_size, y_size,
             problem ? problem : e.describe().c_str());
    failed_ = true;
    return false;
  }
#if !CPL_IS_LSB
  const int bytes = static_cast<int>(mrsv::sampleSize(h.sample_type));
  GDALSwapWords(grid->samples.data(), bytes, x_size * y_size, bytes);  // stored little-endian
#endif
  return true;
}

CPLErr MrsvDataset::readTile(int block_x, int block_y, void* image) {
  int bx = 0, by = 0;
  GetRasterBand(1)->GetBlockSize(&bx, &by);
  // The block's positions; an edge block is cut at the raster's edge.
  const int x = block_x * bx, y = block_y * by;
  const int x_size = std::min(bx, nRasterXSize - x), y_size = std::min(by, nRasterYSize - y);
  mrsv::DecodedGrid grid;
  if (!decodeWindow(x, y, x_size, y_size, 1, &grid)) return CE_Failure;
  const size_t bytes = mrsv::sampleSize(stream_->header.sample_type);
  const size_t row_out = static_cast<size_t>(bx) * bytes, row_in = static_cast<size_t>(x_size) * bytes;
  auto* out = static_cast<uint8_t*>(image);
  std::memset(out, 0, row_out * static_cast<size_t>(by));  // the part of an edge block outside the raster
  for (int row = 0; row < y_size; ++row)
    std::memcpy(out + row * row_out, grid.samples.data() + row * row_in, row_in);
  return CE_None;
}

// A local file by pread; anything else (/vsicurl/, /vsizip/, ...) through
// GDAL's virtual file layer. False with a GDAL error when it cannot be opened.
bool openSource(const char* name, Stream* stream) {
  std::string error;
  stream->source = mrsv::openFileByteSource(name, &error);
  if (stream->source) return true;
  VSILFILE* f = VSIFOpenL(name, "rb");
  VSIStatBufL st;
  if (!f || VSIStatL(name, &st) != 0) {
    if (f) VSIFCloseL(f);
    CPLError(CE_Failure, CPLE_OpenFailed, "%s: cannot open it", name);
    return false;
  }
  stream->source.reset(new VsiByteSource(f, static_cast<uint64_t>(st.st_size)));
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
  if (!openSource(name, stream.get())) return nullptr;
  // GHDR's coding byte (file header 12 bytes, chunk header 8, then sample
  // type, dimensions, coding): 2 is a tiled grid, read by tile.
  if (info->nHeaderBytes >= 12 + 8 + 3 && std::memcmp(info->pabyHeader + 12, "GHDR", 4) == 0 &&
      info->pabyHeader[12 + 8 + 2] == static_cast<uint8_t>(mrsv::GridCoding::kTiled)) {
    stream->tiled = true;
    std::unique_ptr<MrsvDataset> ds = openTiled(name, stream);
    if (!ds) return nullptr;
    ds->SetDescription(name);
    ds->TryLoadXML();
    return ds.release();
  }
  if (mrsv::isProgressiveMeshStream(info->pabyHeader, static_cast<size_t>(info->nHeaderBytes)) ||
      mrsv::isProgressiveTetStream(info->pabyHeader, static_cast<size_t>(info->nHeaderBytes))) {
    CPLError(CE_Failure, CPLE_OpenFailed, "%s: a mesh stream, not a grid", name);
    return nullptr;
  }
  // The chunk headers, walked by offset, locate the bands (an overview reads
  // the prefix that holds its bands) and the first samples chunk; the
  // headers, meta chunk and no-data mask before it are read and decoded, with
  // their checksums. The rest is read when samples are first wanted. A walk
  // that meets a length past the end leaves the framing error to the decode
  // of the whole file.
  size_t samples_offset = 0;
  bool has_samples = false;
  const uint64_t size = stream->source->size();
  for (uint64_t pos = mrsv::kFileHeaderSize; pos + mrsv::kChunkHeaderSize <= size;) {
    uint8_t h[mrsv::kChunkHeaderSize];
    if (!stream->source->read(pos, sizeof h, h)) break;
    const uint64_t length = uint64_t{h[4]} | uint64_t{h[5]} << 8 | uint64_t{h[6]} << 16 | uint64_t{h[7]} << 24;
    const bool band = std::memcmp(h, mrsv::kChunkBand.c, 4) == 0;
    if (band) stream->band_offsets.push_back(pos);
    if ((band || std::memcmp(h, mrsv::kChunkGridStored.c, 4) == 0) && !has_samples) {
      samples_offset = static_cast<size_t>(pos);
      has_samples = true;
    }
    pos += mrsv::kChunkHeaderSize + length + mrsv::kChunkCrcSize;
  }
  const uint64_t head = has_samples ? samples_offset : size;
  if (!stream->ensure(head)) return nullptr;
  mrsv::DecodedGrid grid;
  mrsv::Error e = mrsv::decodeGrid(stream->bytes.data(), stream->bytes.size(), mrsv::DecodeOptions{}, &grid);
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
  if (h.coding == mrsv::GridCoding::kWavelet && grid.wavelet.precinct_log2 > 0) {
    stream->precinct = 1u << grid.wavelet.precinct_log2;
    if (grid.wavelet.order == mrsv::kWaveletOrderCdf97)
      stream->precinct_levels = h.num_dims > 1 ? std::min(grid.wavelet.levels[0], grid.wavelet.levels[1])
                                               : grid.wavelet.levels[0];
  }
  const uint32_t full[2] = {h.size_x, h.num_dims > 1 ? h.size_y : 1};
  std::unique_ptr<MrsvDataset> ds(new MrsvDataset(stream, 0, full, static_cast<size_t>(size)));
  // One overview per wavelet level that reaches the decoded bands (a stream
  // coded by prediction alone, or a stored one, has none).
  if (h.coding == mrsv::GridCoding::kWavelet)
    ds->overview_count_ = std::max(grid.wavelet.levels[0], h.num_dims > 1 ? grid.wavelet.levels[1] : uint8_t{0});
  ds->overviews_.resize(static_cast<size_t>(ds->overview_count_));
  ds->SetDescription(name);
  ds->TryLoadXML();
  return ds.release();
}

std::unique_ptr<MrsvDataset> MrsvDataset::openTiled(const char* name, std::shared_ptr<Stream> stream) {
  mrsv::DecodedGrid probe;
  mrsv::GridRegion one;
  mrsv::Error e = mrsv::decodeGridRegion(*stream->source, one, mrsv::DecodeOptions{}, &probe);
  const mrsv::GridHeader& h = probe.header;
  const char* problem = !e.ok() ? nullptr
                        : h.num_dims > 2 ? "a 3-D grid is not a raster; decode it with mrsv decode"
                        : !probe.has_samples ? "the stream ends before its sample data"
                                             : nullptr;
  if (!e.ok() || problem) {
    CPLError(CE_Failure, CPLE_OpenFailed, "%s: %s", name, problem ? problem : e.describe().c_str());
    return nullptr;
  }
  stream->header = h;
  stream->metadata = std::move(probe.metadata);
  // Reduced by K, every axis steps by 2^K (spec 11.6): the spacing's scale.
  std::fill(stream->wavelet.levels, stream->wavelet.levels + 3, uint8_t{16});
  stream->tile_size[0] = probe.tile_size[0];
  stream->tile_size[1] = h.num_dims > 1 ? probe.tile_size[1] : 1;
  const uint32_t full[2] = {h.size_x, h.num_dims > 1 ? h.size_y : 1};
  std::unique_ptr<MrsvDataset> ds(new MrsvDataset(stream, 0, full, 0));
  // Overview k: the 2^k lattice (spec 11.6), which needs tile sizes that are
  // multiples of 2^k along the axes with more than one tile; down to one
  // block, and no further than 16 levels.
  int count = 0;
  for (int k = 1; k <= 16; ++k) {
    bool fits = (full[0] >> k) >= 1 && (full[1] >> k) >= 1 && (full[0] > 1 || full[1] > 1);
    for (int a = 0; a < 2; ++a)
      if (full[a] > stream->tile_size[a] && stream->tile_size[a] % (1u << k) != 0) fits = false;
    if (!fits) break;
    count = k;
    if ((full[0] >> k) <= stream->tile_size[0] && (full[1] >> k) <= stream->tile_size[1]) break;
  }
  ds->overview_count_ = count;
  ds->overviews_.resize(static_cast<size_t>(count));
  return ds;
}

MrsvDataset* MrsvDataset::overview(int i) {
  if (i < 0 || i >= overview_count_) return nullptr;
  auto& slot = overviews_[static_cast<size_t>(i)];
  if (!slot && tiled()) {
    // Every 2^(i+1)-th sample from sample 0 along each axis (spec 11.6).
    const mrsv::GridHeader& h = stream_->header;
    const uint32_t step = 1u << (i + 1);
    const uint32_t size[2] = {(h.size_x + step - 1) / step, h.num_dims > 1 ? (h.size_y + step - 1) / step : 1};
    slot.reset(new MrsvDataset(stream_, i + 1, size, 0));
    return slot.get();
  }
  if (!slot) {
    mrsv::ReducedResolution r;
    if (!mrsv::reducedResolution(stream_->header, stream_->wavelet, i + 1, &r)) return nullptr;
    // The bands the synthesis uses; a decode of the stream up to the next
    // band gives the same samples (spec 5.8.3) without reading the finer ones.
    const std::vector<uint64_t>& bands = stream_->band_offsets;
    const size_t prefix = r.bands_needed < bands.size() ? bands[r.bands_needed] : stream_->source->size();
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
