// Grid file formats read and written by the tools (never by the decoder):
// headerless raw, NRRD (attached header, raw encoding), PGM (P5 or P2),
// SRTM .hgt and, in builds with GDAL (CMake option MRSV_GDAL), GeoTIFF and
// any other raster GDAL reads. The format is chosen by the file name's
// extension; a file with none of the known extensions and no raw layout is
// offered to GDAL, which recognises rasters by their content.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/grid.h"
#include "mrsv/metadata.h"

namespace mrsv {

enum class GridFormat { kRaw, kNrrd, kPgm, kHgt, kGeoTiff };

// Whether this build reads rasters and writes GeoTIFF through GDAL.
bool gridFormatsHaveGdal();

GridFormat gridFormatOf(const std::string& path);

// The layout of a headerless raw file, from --dims, --type and --endian.
struct RawLayout {
  bool has_layout = false;
  GridHeader header;
  bool big_endian = false;
  // Rasters read through GDAL: the 1-based band to read; 0 reads a raster of
  // one band and refuses one of several (MRSV grids hold one value per sample).
  int band = 0;
};

struct GridInput {
  GridHeader header;             // sizes, sample type; .hgt also sets nodata -32768
  std::vector<uint8_t> samples;  // little-endian, x fastest
  Metadata metadata;             // what the format says: NRRD spacings, .hgt units and CRS,
                                 // a GDAL raster's georeferencing (decision D73)
};

// Reads a grid file; on failure returns false with one line in `error`
// naming the file, where (line, offset or field) and the rule broken.
bool readGridInput(const std::string& path, const RawLayout& raw, GridInput* in, std::string* error);

// The same on bytes already in memory (for the fuzz target and tests):
// `name` stands for the file in errors, `format` replaces its extension.
bool readGridBytes(const std::string& name, GridFormat format, const RawLayout& raw,
                   std::vector<uint8_t> bytes, GridInput* in, std::string* error);

// The bytes of a grid file for `path`'s format: `size` gives the sizes of
// `samples` (smaller than the header's at reduced resolution). Taken by value:
// a caller done with its samples moves them in, and a raw file then is them,
// without a copy. A GeoTIFF takes its georeferencing from `metadata` (origin,
// spacing, crs: decision D73), which at reduced resolution must already hold
// the coarser spacing (reducedResolutionMetadata).
bool encodeGridOutput(const std::string& path, const GridHeader& header,
                      const Metadata& metadata, const uint32_t size[3],
                      std::vector<uint8_t> samples, bool big_endian,
                      std::vector<uint8_t>* out, std::string* error);

// The meta entries of a grid decoded `reduce_levels` levels above the finest
// (spec 5.8.3): output position i stands for sample i * 2^K_a along axis a, so
// `spacing` is multiplied by 2^K_a, K_a = min(reduce_levels, levels[a]);
// `origin` stays. A stored grid (no levels) keeps its spacing.
Metadata reducedResolutionMetadata(const Metadata& metadata, const GridHeader& header,
                                   const uint8_t levels[3], int reduce_levels);
// The metadata of a box of the grid whose first sample is `first`: the origin
// moved there (spacing 1 when the metadata gives none).
Metadata regionMetadata(const Metadata& metadata, const uint32_t first[3]);
// The metadata of the array a whole decode `reduce_levels` levels above the
// finest returns: reducedResolutionMetadata() with the grid's levels, or for
// a tiled grid every 2^K-th sample on every axis (spec 11.6).
Metadata decodedGridMetadata(const DecodedGrid& grid, int reduce_levels);
// The same for a region decode of the box from `lo` (spec 11.5, 11.6): every
// 2^K-th sample on every axis, the origin moved to the first multiple of 2^K
// inside the box.
Metadata decodedRegionMetadata(const DecodedGrid& grid, const uint32_t lo[3], int reduce_levels);

}  // namespace mrsv
