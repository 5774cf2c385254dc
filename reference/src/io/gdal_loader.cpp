// gdal_grid.h for the `mrsv` tool: the GDAL functions come from
// libmrsv_gdal.so (gdal_module.h), opened the first time a file needs GDAL,
// so that the runs which never touch a GeoTIFF (decoding to raw, meshing,
// region decodes) do not load GDAL's libraries at start-up.
//
// The module is looked for in $MRSV_GDAL_MODULE when that is set, else beside
// the executable, else by the dynamic linker's search.
#include <dlfcn.h>
#include <limits.h>
#include <unistd.h>

#include <cstdlib>

#include "io/gdal_grid.h"
#include "io/gdal_module.h"

namespace mrsv {
namespace {

struct Loaded {
  const GdalModule* module = nullptr;
  std::string problem;  // why it is null
};

std::string besideExecutable() {
  char path[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
  if (n <= 0) return "";
  std::string exe(path, static_cast<size_t>(n));
  const size_t slash = exe.rfind('/');
  return slash == std::string::npos ? "" : exe.substr(0, slash + 1) + kGdalModuleFile;
}

Loaded load() {
  Loaded loaded;
  std::string path;
  if (const char* env = std::getenv("MRSV_GDAL_MODULE"); env && *env) {
    path = env;
  } else {
    path = besideExecutable();
    if (path.empty() || access(path.c_str(), F_OK) != 0) path = kGdalModuleFile;
  }
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    loaded.problem = "cannot open the GDAL module " + path + " (" + (why ? why : "unknown reason") +
                     "); set MRSV_GDAL_MODULE to its path";
    return loaded;
  }
  using Entry = const GdalModule* (*)();
  auto entry = reinterpret_cast<Entry>(dlsym(handle, kGdalModuleSymbol));
  const GdalModule* module = entry ? entry() : nullptr;
  if (!module || module->version != kGdalModuleVersion || module->layout != gdalModuleLayout()) {
    loaded.problem = "the GDAL module " + path + " is from another build of mrsv; rebuild it with this one";
    return loaded;  // the handle stays open: closing a library that ran static constructors is not worth the risk
  }
  loaded.module = module;
  return loaded;
}

const Loaded& module() {
  static const Loaded loaded = load();
  return loaded;
}

}  // namespace

bool gdalAvailable() { return module().module != nullptr; }

bool readGdalGrid(const std::string& path, int band, GridInput* in, std::string* error) {
  const Loaded& m = module();
  if (!m.module) {
    *error = path + ": " + m.problem;
    return false;
  }
  return m.module->read_grid(path, band, in, error);
}

bool encodeGeoTiff(const std::string& path, const GridHeader& header, const Metadata& metadata,
                   const uint32_t size[3], const std::vector<uint8_t>& samples, std::vector<uint8_t>* out,
                   std::string* error) {
  const Loaded& m = module();
  if (!m.module) {
    *error = path + ": " + m.problem;
    return false;
  }
  return m.module->encode_geotiff(path, header, metadata, size, samples, out, error);
}

}  // namespace mrsv
