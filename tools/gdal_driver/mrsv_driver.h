// The pieces of the MRSV GDAL driver plugin that its files share: opening a
// .mrsv (mrsv_driver.cpp) and writing one (mrsv_create_copy.cpp).
#pragma once

#include <gdal_priv.h>

// Opens a 1-D or 2-D grid stream; reads its headers and metadata only, and
// decodes a resolution when its samples are first asked for.
GDALDataset* mrsvOpen(GDALOpenInfo* info);

// gdal_translate -of MRSV: band 1 of `source` encoded as `mrsv encode` would
// encode the same raster with the options that `options` name.
GDALDataset* mrsvCreateCopy(const char* filename, GDALDataset* source, int strict, char** options,
                            GDALProgressFunc progress, void* progress_data);

// The DMD_CREATIONOPTIONLIST XML of the options mrsvCreateCopy takes.
extern const char kMrsvCreationOptionList[];
