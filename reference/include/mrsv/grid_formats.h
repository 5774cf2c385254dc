// Grid file formats read and written by the tools (never by the decoder):
// headerless raw, NRRD (attached header, raw encoding), PGM (P5 or P2) and
// SRTM .hgt. The format is chosen by the file name's extension.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/grid.h"
#include "mrsv/metadata.h"

namespace mrsv {

enum class GridFormat { kRaw, kNrrd, kPgm, kHgt };

GridFormat gridFormatOf(const std::string& path);

// The layout of a headerless raw file, from --dims, --type and --endian.
struct RawLayout {
  bool has_layout = false;
  GridHeader header;
  bool big_endian = false;
};

struct GridInput {
  GridHeader header;             // sizes, sample type; .hgt also sets nodata -32768
  std::vector<uint8_t> samples;  // little-endian, x fastest
  Metadata metadata;             // what the format says: NRRD spacings, .hgt units and CRS
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
// without a copy.
bool encodeGridOutput(const std::string& path, const GridHeader& header, const uint32_t size[3],
                      std::vector<uint8_t> samples, bool big_endian,
                      std::vector<uint8_t>* out, std::string* error);

}  // namespace mrsv
