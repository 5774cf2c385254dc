// The GDAL module (libmrsv_gdal.so): gdal_grid.cpp built as a shared object
// that the `mrsv` tool opens only when a file needs GDAL (gdal_loader.cpp).
// GDAL pulls in about 110 shared libraries whose loading and relocation cost
// every run of the tool 10 ms or more, as much as a small region decode.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/grid.h"
#include "mrsv/grid_formats.h"
#include "mrsv/metadata.h"

namespace mrsv {

// Changes whenever GdalModule or the types it passes change; the loader
// refuses a module of another version (the module and the tool come from one
// build, but a stale module can stand beside a new tool).
constexpr uint32_t kGdalModuleVersion = 1;

struct GdalModule {
  uint32_t version;
  // sizeof(GridInput) + sizeof(GridHeader) + sizeof(Metadata) of the build, a
  // second guard against a module compiled with other definitions.
  uint32_t layout;
  bool (*read_grid)(const std::string& path, int band, GridInput* in, std::string* error);
  bool (*encode_geotiff)(const std::string& path, const GridHeader& header, const Metadata& metadata,
                         const uint32_t size[3], const std::vector<uint8_t>& samples,
                         std::vector<uint8_t>* out, std::string* error);
};

constexpr uint32_t gdalModuleLayout() {
  return static_cast<uint32_t>(sizeof(GridInput) + sizeof(GridHeader) + sizeof(Metadata));
}

}  // namespace mrsv

// The module's one exported symbol.
extern "C" const mrsv::GdalModule* mrsv_gdal_module();
constexpr const char kGdalModuleSymbol[] = "mrsv_gdal_module";
constexpr const char kGdalModuleFile[] = "libmrsv_gdal.so";
