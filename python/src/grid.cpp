// mrsv.encode and mrsv.decode: numpy arrays to and from grid streams (spec 3-5).
//
// Axis order: a numpy array in C order with shape (z, y, x) (2-D: (y, x), 1-D:
// (x,)) has the last axis varying fastest, which is the format's x-fastest
// sample order, so the array's memory is the stream's sample order and no
// transposition is ever made. Metadata that lists axes (spacing, origin) keeps
// the file's x, y, z order.
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>

#include <pybind11/stl.h>

#include "common.h"
#include "region.h"
#include "mrsv/encode.h"
#include "mrsv/file_io.h"
#include "mrsv/grid.h"
#include "mrsv/grid_formats.h"
#include "mrsv/limits.h"

namespace mrsv::python {
namespace {

// Little-endian numpy dtypes of the six sample types (spec 3.1): the stream's
// byte order, right on any host.
const char* dtypeOf(SampleType type) {
  switch (type) {
    case SampleType::kUint8: return "<u1";
    case SampleType::kInt16: return "<i2";
    case SampleType::kUint16: return "<u2";
    case SampleType::kInt32: return "<i4";
    case SampleType::kFloat32: return "<f4";
    case SampleType::kFloat64: return "<f8";
  }
  return "<u1";
}

const char kTypes[] = "uint8, int16, uint16, int32, float32, float64";

// The no-data value as the sample type's bit pattern (as 'mrsv encode --nodata').
uint64_t nodataBits(const py::object& value, SampleType type) {
  bool is_float = type == SampleType::kFloat32 || type == SampleType::kFloat64;
  if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value) ||
                                            py::hasattr(value, "__index__") || py::hasattr(value, "__float__")))
    throw py::type_error("nodata= must be a number or None");
  double v = value.cast<double>();
  if (is_float) {
    if (type == SampleType::kFloat64) {
      uint64_t bits;
      std::memcpy(&bits, &v, 8);
      return bits;
    }
    float f = static_cast<float>(v);
    if (std::isfinite(v) && !std::isfinite(f)) throw py::value_error("nodata= is out of range for float32");
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    return bits;
  }
  if (!std::isfinite(v) || v != std::floor(v))
    throw py::value_error(std::string("nodata= must be a whole number for ") + sampleTypeName(type) + " samples");
  double lo = 0, hi = 0;
  switch (type) {
    case SampleType::kUint8: hi = 255; break;
    case SampleType::kInt16: lo = -32768; hi = 32767; break;
    case SampleType::kUint16: hi = 65535; break;
    default: lo = std::numeric_limits<int32_t>::min(); hi = std::numeric_limits<int32_t>::max();
  }
  if (v < lo || v > hi)
    throw py::value_error("nodata= " + std::to_string(static_cast<long long>(v)) + " is out of range for " +
                          sampleTypeName(type));
  uint64_t mask = (uint64_t{1} << (8 * sampleSize(type))) - 1;
  return static_cast<uint64_t>(static_cast<int64_t>(v)) & mask;
}

py::object nodataValue(const GridHeader& h) {
  if (!h.hasNodata()) return py::none();
  uint64_t b = h.nodata_bits;
  switch (h.sample_type) {
    case SampleType::kUint8:
    case SampleType::kUint16: return py::int_(b);
    case SampleType::kInt16: return py::int_(static_cast<int16_t>(b));
    case SampleType::kInt32: return py::int_(static_cast<int32_t>(b));
    case SampleType::kFloat32: {
      float f;
      uint32_t u = static_cast<uint32_t>(b);
      std::memcpy(&f, &u, 4);
      return py::float_(f);
    }
    case SampleType::kFloat64: {
      double d;
      std::memcpy(&d, &b, 8);
      return py::float_(d);
    }
  }
  return py::none();
}

// A number-list of spec 2.6 (x, y, z order) from a sequence of `dims` numbers.
std::string numberList(const py::object& values, const char* what, int dims) {
  std::vector<double> v;
  try {
    v = values.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    throw py::type_error(std::string(what) + "= must be a sequence of numbers (x, y, z order)");
  }
  if (static_cast<int>(v.size()) != dims)
    throw py::value_error(std::string(what) + "= must give " + std::to_string(dims) +
                          " numbers, one per axis in x, y, z order");
  std::string text;
  for (double x : v) {
    if (!std::isfinite(x)) throw py::value_error(std::string(what) + "= must be finite");
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    text += (text.empty() ? "" : ",") + std::string(buf);
  }
  return text;
}

// A metadata number-list or number back as floats; None when absent or not one.
py::object parsedNumbers(const Metadata& m, const char* key, bool list) {
  const std::string* text = m.find(key);
  if (!text) return py::none();
  py::list out;
  size_t start = 0;
  while (start <= text->size()) {
    size_t comma = list ? text->find(',', start) : std::string::npos;
    if (comma == std::string::npos) comma = text->size();
    std::string item = text->substr(start, comma - start);
    char* end = nullptr;
    double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0') return py::none();
    out.append(v);
    start = comma + 1;
  }
  return list ? py::object(py::tuple(out)) : out[0];
}

double checkedNumber(const std::optional<double>& v, const char* name, double lo, double hi) {
  if (!(*v >= lo && *v <= hi))
    throw py::value_error(std::string(name) + "= must be a number from " + py::str(py::float_(lo)).cast<std::string>() +
                          " to " + py::str(py::float_(hi)).cast<std::string>());
  return *v;
}

// region = ("box", lo, hi) or ("ellipsoid", centre, semi_axes), x, y, z order.
RegionOfInterest parseRegion(const py::object& region, int dims) {
  RegionOfInterest roi;
  std::string shape;
  std::vector<double> a, b;
  try {
    auto t = region.cast<std::tuple<std::string, std::vector<double>, std::vector<double>>>();
    std::tie(shape, a, b) = t;
  } catch (const py::cast_error&) {
    throw py::type_error("roi= must be ('box', lo, hi) or ('ellipsoid', centre, semi_axes), points in x, y, z order");
  }
  if (shape != "box" && shape != "ellipsoid") throw py::value_error("roi= shape must be 'box' or 'ellipsoid'");
  if (a.size() != b.size() || a.size() < 2 || a.size() > 3 || static_cast<int>(a.size()) > std::max(dims, 2))
    throw py::value_error("roi= points must have 2 or 3 coordinates each (x, y[, z]), as many as the grid's axes");
  roi.ellipsoid = shape == "ellipsoid";
  for (size_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a[i]) || !std::isfinite(b[i])) throw py::value_error("roi= coordinates must be finite");
    if (roi.ellipsoid) {
      if (!(b[i] > 0)) throw py::value_error("roi= semi-axes must be positive");
      roi.center[i] = a[i];
      roi.half_size[i] = b[i];
    } else {
      double lo = std::min(a[i], b[i]), hi = std::max(a[i], b[i]);
      roi.center[i] = 0.5 * (lo + hi);
      roi.half_size[i] = 0.5 * (hi - lo);
    }
  }
  return roi;
}

// The grid header and samples of an array; raises TypeError or ValueError.
GridHeader headerOf(const py::object& array_like, py::array* samples) {
  py::module_ np = py::module_::import("numpy");
  py::array a = np.attr("asarray")(array_like);
  SampleType type;
  std::string name = py::str(a.dtype().attr("name"));
  if (!parseSampleType(name, &type))
    throw py::type_error("dtype " + name + " is not a sample type of the format; use one of " + kTypes +
                         " (e.g. array.astype(numpy.int32))");
  if (a.ndim() < 1 || a.ndim() > 3)
    throw py::value_error("the array must have 1 to 3 dimensions ((x,), (y, x) or (z, y, x)), not " +
                          std::to_string(a.ndim()));
  GridHeader h;
  h.num_dims = static_cast<uint8_t>(a.ndim());
  h.sample_type = type;
  uint32_t* sizes[3] = {&h.size_x, &h.size_y, &h.size_z};
  for (int axis = 0; axis < a.ndim(); ++axis) {
    py::ssize_t n = a.shape(a.ndim() - 1 - axis);  // the last numpy axis is x
    if (n < 1 || n > static_cast<py::ssize_t>(UINT32_MAX))
      throw py::value_error("every axis needs 1 to 2^32-1 samples, not " + std::to_string(n));
    *sizes[axis] = static_cast<uint32_t>(n);
  }
  if (std::string problem = gridHeaderProblem(h); !problem.empty()) throw py::value_error(problem);
  *samples = np.attr("ascontiguousarray")(a, py::dtype(dtypeOf(type)));
  return h;
}

// tile= (an int for every axis, or one per axis in x, y, z order) as
// 'mrsv encode --tile' reads it; empty for None.
std::vector<uint32_t> tileSizes(const py::object& tile) {
  if (tile.is_none()) return {};
  const char* form = "tile= must be an int or a sequence of 1 to 3 ints (x, y, z order)";
  std::vector<py::object> items;
  if (py::isinstance<py::sequence>(tile) && !py::isinstance<py::str>(tile) && !py::isinstance<py::bytes>(tile)) {
    for (const py::handle& v : py::reinterpret_borrow<py::sequence>(tile))
      items.push_back(py::reinterpret_borrow<py::object>(v));
  } else {
    items.push_back(tile);
  }
  if (items.empty()) throw py::value_error(form);
  if (items.size() > 3) throw py::value_error("tile= takes at most 3 sizes");
  std::vector<uint32_t> sizes;
  for (const py::object& v : items) {
    if (py::isinstance<py::bool_>(v) || py::isinstance<py::float_>(v) || !py::hasattr(v, "__index__"))
      throw py::type_error(form);
    const long long n = v.attr("__index__")().cast<long long>();
    if (n < 1 || n > static_cast<long long>(kMaxGridAxis))
      throw py::value_error("tile= size " + std::to_string(n) + " is not a whole number from 1 to " +
                            std::to_string(kMaxGridAxis));
    sizes.push_back(static_cast<uint32_t>(n));
  }
  return sizes;
}

py::dict encode(const py::object& array, const py::object& path, const py::object& nodata,
                const std::string& coding, const std::optional<std::string>& wavelet_name,
                const std::optional<int>& order, const std::string& entropy, int levels, bool lossless,
                const std::optional<double>& max_error, const std::optional<double>& bits_per_sample,
                const std::optional<double>& psnr, const std::optional<double>& step,
                const std::optional<double>& keep, bool progressive, const std::string& bound_route,
                const std::string& prediction, const py::object& roi, double roi_falloff, double roi_gain,
                const py::object& spacing, const py::object& origin, const py::object& metadata_entries,
                const py::object& tile, const py::object& threads, const py::object& precinct) {
  py::array samples;
  GridHeader header = headerOf(array, &samples);
  std::string out = outputPath(path);
  if (!nodata.is_none()) {
    header.nodata_bits = nodataBits(nodata, header.sample_type);
    header.grid_flags |= kGridFlagHasNodata;
  }
  // The options as 'mrsv encode' checks them (tools/mrsv/cmd_encode.cpp).
  if (coding != "wavelet" && coding != "stored") throw py::value_error("coding= must be 'wavelet' or 'stored'");
  WaveletEncodeOptions w;
  if (max_error) w.max_error = checkedNumber(max_error, "max_error", 0, 524287);
  if (bits_per_sample) w.bits_per_sample = checkedNumber(bits_per_sample, "bits_per_sample", 1e-3, 64);
  if (psnr) w.psnr = checkedNumber(psnr, "psnr", 1, 400);
  if (step) w.step = checkedNumber(step, "step", 1e-12, 1e300);
  if (keep) w.keep_fraction = checkedNumber(keep, "keep", 1e-9, 1);
  if (lossless) w.max_error = 0;
  const int targets = bool(max_error) + bool(bits_per_sample) + bool(psnr) + bool(step) + bool(keep) + lossless;
  if (targets > 1)
    throw py::value_error("give at most one of lossless, max_error, bits_per_sample, psnr, step, keep");
  if (targets == 0) w.max_error = 0;  // lossless by default, as the CLI
  if (coding == "stored" && ((targets > 0 && !lossless) || order || wavelet_name || progressive || !roi.is_none()))
    throw py::value_error("coding='stored' takes no rate, quality or wavelet option");
  if (levels < 0 || levels > 16) throw py::value_error("levels= must be a whole number from 0 to 16");
  w.max_levels = levels;
  if (entropy == "baseline") w.entropy_mode = kEntropyBaseline;
  else if (entropy != "adaptive") throw py::value_error("entropy= must be 'adaptive' or 'baseline'");
  if (prediction == "neighbour") w.prediction = WaveletEncodeOptions::Prediction::kNeighbour;
  else if (prediction == "weighted") w.prediction = WaveletEncodeOptions::Prediction::kWeighted;
  else if (prediction != "auto") throw py::value_error("prediction= must be 'auto', 'neighbour' or 'weighted'");
  if (w.prediction == WaveletEncodeOptions::Prediction::kWeighted && w.entropy_mode == kEntropyBaseline)
    throw py::value_error("prediction='weighted' needs entropy='adaptive'");
  if (bound_route == "residual") w.bound_route = WaveletEncodeOptions::BoundRoute::kResidual;
  else if (bound_route == "predictive") w.bound_route = WaveletEncodeOptions::BoundRoute::kPredictive;
  else if (bound_route != "auto") throw py::value_error("bound_route= must be 'auto', 'residual' or 'predictive'");
  if (bound_route != "auto" && w.max_error < 0)
    throw py::value_error("bound_route= goes with lossless or max_error");
  if (w.bound_route == WaveletEncodeOptions::BoundRoute::kPredictive && progressive)
    throw py::value_error("bound_route='predictive' is not progressive; drop one of them");
  w.progressive = progressive;
  if (!roi.is_none()) {
    if (w.max_error >= 0)
      throw py::value_error("roi= goes with step, bits_per_sample, psnr or keep (lossless and error-bounded "
                            "coding are exact everywhere)");
    w.roi = parseRegion(roi, header.num_dims);
    w.has_roi = true;
  }
  w.roi.falloff = checkedNumber(roi_falloff, "roi_falloff", 0, 1e9);
  w.roi_gain = checkedNumber(roi_gain, "roi_gain", 1, 1e6);
  const std::string family = wavelet_name ? *wavelet_name : order ? "bspline" : "cdf97";
  if (family == "cdf97") {
    if (order) throw py::value_error("order= is for wavelet='bspline'");
    w.order = kWaveletOrderCdf97;
  } else if (family == "bspline") {
    w.order = order ? *order : 2;
    if (w.order < 1 || w.order > 4) throw py::value_error("order= must be 1 to 4 (Haar, linear, quadratic, cubic)");
  } else {
    throw py::value_error("wavelet= must be 'cdf97' or 'bspline'");
  }
  // Tiles as 'mrsv encode --tile' takes them (spec 11).
  const std::vector<uint32_t> tiles = tileSizes(tile);
  TiledEncodeOptions tiled;
  tiled.threads = threadCount(threads);
  if (!tiles.empty()) {
    if (coding == "stored") throw py::value_error("tile= needs coding='wavelet'");
    if (tiles.size() != 1 && tiles.size() != header.num_dims)
      throw py::value_error("tile= gives " + std::to_string(tiles.size()) + " sizes for a grid of " +
                            std::to_string(header.num_dims) + " dimensions (give 1 or " +
                            std::to_string(header.num_dims) + ")");
    if (w.has_roi) throw py::value_error("tile= does not take roi= (no region of interest with tiles in this version)");
    for (int a = 0; a < 3; ++a)
      tiled.tile_size[a] = a >= header.num_dims ? 1 : tiles[std::min<size_t>(a, tiles.size() - 1)];
  }
  if (!precinct.is_none()) {  // as 'mrsv encode --precinct' (spec 5.7.6)
    if (coding == "stored") throw py::value_error("precinct= needs coding='wavelet'");
    if (!tiles.empty()) throw py::value_error("precinct= and tile= are two ways to cut a grid; give one");
    const long long n = py::cast<long long>(precinct);
    for (int p = kMinPrecinctLog2; p <= kMaxPrecinctLog2; ++p)
      if (n == (1ll << p)) w.precinct_log2 = p;
    if (w.precinct_log2 == 0)
      throw py::value_error("precinct= must be a power of two from " + std::to_string(1 << kMinPrecinctLog2) +
                            " to " + std::to_string(1 << kMaxPrecinctLog2));
  }
  Metadata metadata;
  if (!spacing.is_none()) metadata.set("spacing", numberList(spacing, "spacing", header.num_dims));
  if (!origin.is_none()) metadata.set("origin", numberList(origin, "origin", header.num_dims));
  addMetadata(metadata_entries, &metadata);

  const uint8_t* p = static_cast<const uint8_t*>(samples.data());
  std::vector<uint8_t> bytes(p, p + samples.nbytes());
  std::vector<uint8_t> stream;
  WaveletEncodeReport report;
  Error e;
  std::string io_error;
  bool written = false;
  {
    py::gil_scoped_release release;
    e = coding == "stored" ? encodeStoredGrid(header, bytes, metadata, &stream)
        : tiles.empty()    ? encodeWaveletGrid(header, bytes, metadata, w, &stream, &report)
                           : encodeTiledGrid(header, bytes, metadata, w, tiled, &stream, &report);
    if (e.ok()) written = writeFileAtomically(out, stream, &io_error);
  }
  if (!e.ok()) throw py::value_error(e.field + ": " + e.message);
  if (!written) {
    PyErr_SetString(PyExc_OSError, (out + ": " + io_error).c_str());
    throw py::error_already_set();
  }
  py::dict r;
  r["bytes"] = stream.size();
  r["bits_per_sample"] = 8.0 * stream.size() / static_cast<double>(header.sampleCount());
  if (coding == "wavelet") {
    r["psnr"] = report.psnr;
    r["max_abs_error"] = report.max_abs_error;
    r["levels"] = report.levels;  // tiled: the most levels of any tile
    if (tiles.empty()) {
      r["kept_coefficients"] = report.kept_coefficients;
      r["l2_error"] = report.l2_error;
    } else {
      std::vector<uint32_t> size(tiled.tile_size, tiled.tile_size + header.num_dims);
      r["tile_size"] = py::tuple(py::cast(size));  // x, y, z order
    }
  } else {
    r["psnr"] = std::numeric_limits<double>::infinity();
    r["max_abs_error"] = 0.0;
    r["levels"] = 0;
  }
  return r;
}

// The samples of a decode as a numpy array of shape (z, y, x).
py::array samplesArray(const DecodedGrid& grid) {
  const GridHeader& h = grid.header;
  std::vector<py::ssize_t> shape;
  for (int axis = h.num_dims - 1; axis >= 0; --axis) shape.push_back(grid.output_size[axis]);
  py::array samples(py::dtype(dtypeOf(h.sample_type)), shape);
  std::memcpy(samples.mutable_data(), grid.samples.data(), grid.samples.size());
  return samples;
}

// What a whole decode and a region decode both report; spacing and origin are
// the caller's (they describe the array returned).
py::dict gridInfo(const DecodedGrid& grid, int levels) {
  const GridHeader& h = grid.header;
  py::dict info;
  std::vector<py::ssize_t> full;
  const uint32_t sizes[3] = {h.size_x, h.size_y, h.size_z};
  for (int axis = h.num_dims - 1; axis >= 0; --axis) full.push_back(sizes[axis]);
  info["shape"] = py::tuple(py::cast(full));
  info["sample_type"] = sampleTypeName(h.sample_type);
  info["coding"] = h.coding == GridCoding::kStored ? "stored" : h.coding == GridCoding::kTiled ? "tiled" : "wavelet";
  info["nodata"] = nodataValue(h);
  if (h.coding != GridCoding::kStored) {
    // A tiled grid: the first tile decoded says which wavelet (each tile is a
    // wavelet grid of its own, spec 11.4); the bands are summed over the tiles
    // decoded (a region's only).
    info["wavelet"] = grid.wavelet.order == kWaveletOrderCdf97 ? "cdf97" : "bspline";
    info["order"] = grid.wavelet.order == kWaveletOrderCdf97 ? py::object(py::none()) : py::int_(grid.wavelet.order);
    info["bands_decoded"] = grid.bands_decoded;
    info["bands_total"] = grid.bands_total;
  }
  if (h.coding == GridCoding::kWavelet) {
    std::vector<int> per_axis(grid.wavelet.levels, grid.wavelet.levels + h.num_dims);
    info["decomposition_levels"] = py::tuple(py::cast(per_axis));  // x, y, z order
    info["residual_decoded"] = grid.residual_decoded;
  }
  if (h.coding == GridCoding::kTiled) {
    std::vector<uint32_t> tile(grid.tile_size, grid.tile_size + h.num_dims);
    info["tile_size"] = py::tuple(py::cast(tile));  // x, y, z order
    info["tiles_total"] = grid.tiles_total;
  }
  info["levels"] = levels;
  info["metadata"] = metadataDict(grid.metadata);
  for (const char* key : {"error_bound", "error_max_abs", "error_psnr_db", "error_rmse"})
    info[key] = parsedNumbers(grid.metadata, key, false);
  return info;
}

py::tuple decodeBox(const py::object& source_object, int levels, const py::object& byte_limit,
                    const py::object& region_object, int threads) {
  const RegionArgument region = parseGridRegion(region_object);
  DecodeOptions options;
  options.reduce_levels = levels;
  options.threads = threads;
  RegionDecode r = decodeRegion(source_object, byte_limit, region, options);
  const DecodedGrid& grid = r.grid;
  if (!grid.has_samples) throw py::value_error("the stream ends before the region's sample data");
  py::dict info = gridInfo(grid, levels);
  info["region"] = regionTuple(region);
  info["complete"] = py::none();  // a region decode reads only part of the stream
  info["bytes"] = r.bytes_total;
  info["bytes_read"] = r.bytes_read;
  info["bytes_used"] = py::none();
  // The metadata 'mrsv decode --region' writes.
  const Metadata output_metadata = decodedRegionMetadata(grid, region.box.lo, levels);
  info["spacing"] = parsedNumbers(output_metadata, "spacing", true);
  info["origin"] = parsedNumbers(output_metadata, "origin", true);
  return py::make_tuple(samplesArray(grid), info);
}

py::tuple decode(const py::object& source_object, int levels, const py::object& byte_limit,
                 const py::object& region, const py::object& threads_object) {
  if (levels < 0 || levels > 16) throw py::value_error("levels= must be a whole number from 0 to 16");
  const int threads = threadCount(threads_object);
  if (!region.is_none()) return decodeBox(source_object, levels, byte_limit, region, threads);
  Source source = loadSource(source_object);
  DecodeOptions options;
  options.reduce_levels = levels;
  options.threads = threads;
  options.container.allow_partial_tail = applyByteLimit(byte_limit, &source);
  refuseMeshStreams(source.data, source.size);
  DecodedGrid grid;
  Error e;
  {
    py::gil_scoped_release release;
    e = decodeGrid(source.data, source.size, options, &grid);
  }
  // A tiled grid whose tiles are not on the 2^K lattice (spec 11.6).
  if (e.status == Status::kInvalidArgument && e.field == "reduce_levels") throw py::value_error("levels=: " + e.message);
  if (!e.ok()) raiseStreamError(e);
  if (!grid.has_samples)
    throw py::value_error("the stream ends before its sample data (a prefix of " +
                          std::to_string(grid.container.chunks.size()) + " chunks)");
  py::dict info = gridInfo(grid, levels);
  info["complete"] = grid.container.complete;
  info["bytes"] = source.size;
  info["bytes_read"] = source.size;
  info["bytes_used"] = grid.container.complete ? grid.container.end_chunk_offset + kChunkHeaderSize + kChunkCrcSize
                       : grid.container.chunks.empty() ? kFileHeaderSize
                                                       : grid.container.chunks.back().endOffset();
  // spacing and origin describe the array returned: at reduced resolution an
  // output step spans 2^K samples, as in `mrsv decode --levels K`'s GeoTIFF
  // (metadata keeps the stream's own entries).
  const Metadata output_metadata = decodedGridMetadata(grid, levels);
  info["spacing"] = parsedNumbers(output_metadata, "spacing", true);
  info["origin"] = parsedNumbers(output_metadata, "origin", true);
  return py::make_tuple(samplesArray(grid), info);
}

}  // namespace

void registerGrid(py::module_& m) {
  m.def("encode", &encode, py::arg("array"), py::arg("path"), py::kw_only(), py::arg("nodata") = py::none(),
        py::arg("coding") = "wavelet", py::arg("wavelet") = py::none(), py::arg("order") = py::none(),
        py::arg("entropy") = "adaptive", py::arg("levels") = 16, py::arg("lossless") = false,
        py::arg("max_error") = py::none(), py::arg("bits_per_sample") = py::none(), py::arg("psnr") = py::none(),
        py::arg("step") = py::none(), py::arg("keep") = py::none(), py::arg("progressive") = false,
        py::arg("bound_route") = "auto", py::arg("prediction") = "auto", py::arg("roi") = py::none(),
        py::arg("roi_falloff") = 16.0, py::arg("roi_gain") = 8.0, py::arg("spacing") = py::none(),
        py::arg("origin") = py::none(), py::arg("metadata") = py::none(), py::arg("tile") = py::none(),
        py::arg("threads") = py::none(), py::arg("precinct") = py::none(),
        R"doc(Encode a grid of samples into an MRSV file (as 'mrsv encode').

array: 1 to 3 dimensions, numpy C order (x,), (y, x) or (z, y, x): the last
  axis is x, the format's fastest axis. dtype uint8, int16, uint16, int32,
  float32 or float64.
path: the output file (written under a temporary name, then renamed).
Rate or quality, at most one (default: lossless): lossless=True,
  max_error=D, bits_per_sample=R, psnr=P, step=S, keep=F. Float samples
  are coded lossily: give them bits_per_sample, psnr, step or keep.
Other options as the CLI's: nodata, coding ('wavelet'|'stored'),
  wavelet ('cdf97'|'bspline'), order (1-4, B-splines), entropy
  ('adaptive'|'baseline'), levels (0-16), progressive, bound_route
  ('auto'|'residual'|'predictive'), prediction ('auto'|'neighbour'|'weighted'),
  roi (('box', lo, hi) or ('ellipsoid', centre, semi_axes), x, y, z order),
  roi_falloff, roi_gain. spacing, origin: per axis in x, y, z order (the
  meta chunk's order); metadata: a dict of str to str (spec 2.6).
tile: a tiled stream (spec 11, as 'mrsv encode --tile'): an int for every
  axis or one size per axis in x, y, z order (like spacing), e.g. 256 (2-D)
  or 64 (3-D). Each tile is coded on its own, so that decode(region=...)
  reads only the tiles a box touches. Needs coding='wavelet'; not with roi.
  An error bound holds on every sample; a rate or PSNR target for the whole
  grid (one step for all tiles).
precinct: every band coded in blocks apart, each within a precinct of this
  many samples per axis (a power of two, 16 to 2^24; spec 5.7.6, as 'mrsv
  encode --precinct'): one transform of the whole grid, so a lossy stream
  loses about half what tiles lose. Not with tile=.
threads: tiles coded at once (default: one per core); the stream is the
  same whatever the count.
Returns a dict: bytes, bits_per_sample, psnr, max_abs_error, levels (tiled:
the most of any tile), kept_coefficients and l2_error (untiled wavelet),
tile_size (tiled, x, y, z order).)doc");
  m.def("decode", &decode, py::arg("source"), py::kw_only(), py::arg("levels") = 0, py::arg("bytes") = py::none(),
        py::arg("region") = py::none(), py::arg("threads") = py::none(),
        R"doc(Decode an MRSV grid (as 'mrsv decode').

source: a path or the stream's bytes.
levels: reduced resolution, stop the synthesis this many levels above the
  finest. A tiled stream needs tile sizes that are multiples of 2^levels on
  every axis with more than one tile (spec 11.6).
bytes: read only the first N bytes, as if the rest had not arrived.
region: decode only a box (as 'mrsv decode --region', spec 11.5):
  ((x0, y0[, z0]), (x1, y1[, z1])), the samples x0 <= x < x1, y0 <= y < y1
  (z0 <= z < z1), corners in x, y, z order like spacing, one number per
  axis of the grid. The array returned is in numpy order, shape
  (z1 - z0, y1 - y0, x1 - x0), and equals
  decode(source)[0][z0:z1, y0:y1, x0:x1]. From a path (without bytes) a
  tiled stream reads only its header part and the tiles the box touches
  (info['bytes_read']); other streams are decoded whole and cropped. With
  levels=K, the samples of the box on the lattice of every 2^K-th sample.
threads: tiles decoded at once (default: one per core); the samples are the
  same whatever the count.
Returns (array, info): the samples in numpy C order (z, y, x) with the
stream's dtype, and a dict: shape (the whole grid's, numpy order),
sample_type, coding ('stored', 'wavelet' or 'tiled'), nodata, wavelet,
order, bands_decoded, bands_total (tiled: summed over the tiles decoded),
decomposition_levels and
residual_decoded (untiled wavelet), tile_size (tiled, x, y, z order),
tiles_total (tiled), levels, region (the box, as given, or absent),
complete (None with region: only part of the stream is read), bytes,
bytes_read (from the source: with region from a path, what the box needed),
bytes_used (None with region), metadata, spacing, origin (x, y, z order, of
the array returned: with levels, spacing is 2^K times the stream's on an
axis of K or more levels (every axis of a tiled grid or a region); with
region, origin is moved to the box's first sample, as 'mrsv decode
--region' writes it, when the stream gives an origin), error_bound,
error_max_abs, error_psnr_db, error_rmse.
Raises mrsv.Error when the stream breaks a rule, ValueError for a box
outside the grid or levels the tiling does not allow.)doc");
}

}  // namespace mrsv::python
