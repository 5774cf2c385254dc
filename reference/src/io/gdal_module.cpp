// The entry point of libmrsv_gdal.so (gdal_module.h): the GDAL readers and
// writer of gdal_grid.cpp behind one exported table.
#include "io/gdal_module.h"

#include "io/gdal_grid.h"

extern "C" __attribute__((visibility("default"))) const mrsv::GdalModule* mrsv_gdal_module() {
  static const mrsv::GdalModule module{mrsv::kGdalModuleVersion, mrsv::gdalModuleLayout(), &mrsv::readGdalGrid,
                                       &mrsv::encodeGeoTiff};
  return &module;
}
