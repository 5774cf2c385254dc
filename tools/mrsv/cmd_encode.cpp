// mrsv encode: raw samples in, an MRSV file out.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <thread>
#include <vector>

#include "cli.h"
#include "commands.h"
#include "mrsv/encode.h"
#include "mrsv/file_io.h"
#include "mrsv/grid_formats.h"
#include "mrsv/raw_grid.h"

namespace mrsv::cli {
namespace {

const char kHelp[] =
    "Usage: mrsv encode [options] IN OUT.mrsv\n"
    "\n"
    "(With a mesh IN.obj, IN.ply or IN.off, this encodes a progressive mesh instead:\n"
    "see 'mrsv encode --help x.obj'. With a tet mesh IN.mesh, .node, .ele, .vtu or .vtk,\n"
    "a progressive tet mesh: see 'mrsv encode --help x.vtu'.)\n"
    "\n"
    "Encode a grid of samples (a terrain, an image, a volume) into an MRSV file.\n"
    "IN is chosen by its extension: .nrrd (attached header, raw encoding), .pgm (P5 or\n"
    "P2, 8 or 16 bit), .hgt (SRTM: square big-endian int16, voids -32768), .tif/.tiff (GeoTIFF,\n"
    "through GDAL), or else a headerless raw file (x fastest, then y, then z) described by\n"
    "--dims and --type. Without --dims, a build with GDAL reads any raster GDAL reads\n"
    "(.vrt, .asc, .dem, ...); its georeferencing goes into the meta chunk: origin (the centre\n"
    "of pixel 0,0), spacing (the signed pixel sizes: negative y for north up; row 0 is\n"
    "the raster's first row), crs (EPSG:n or WKT), and its no-data value (decision D73).\n"
    "\n"
    "Input:\n"
    "  --dims X[,Y[,Z]]      grid size in samples (raw input)\n"
    "  --type T              sample type: uint8, int16, uint16, int32, float32, float64 (raw input)\n"
    "  --endian little|big   byte order of IN (default little)\n"
    "  --band N              the band of a multi-band raster read through GDAL (1-based)\n"
    "  --nodata V            sample value that marks missing data, e.g. -32768 for SRTM voids\n"
    "                        (overrides the raster's own no-data value)\n"
    "\n"
    "Coding (default: wavelet, lossless):\n"
    "  --coding wavelet|stored  wavelet: B-spline wavelet coding (spec 4, 5); stored: raw samples\n"
    "  --wavelet W           cdf97: the CDF 9/7 wavelet of JPEG 2000 (spec 4.11; default:\n"
    "                        2 to 5 dB better than the B-splines on the test data);\n"
    "                        bspline: the paper's semi-orthogonal B-spline wavelets (4.2-4.10)\n"
    "  --order K             B-spline order 1..4: Haar, linear, quadratic, cubic (default 2;\n"
    "                        implies --wavelet bspline)\n"
    "  --entropy M           adaptive (context-modelled range coding; default) or baseline\n"
    "                        (the paper's JPEG-like run/size symbols with Huffman tables)\n"
    "  --levels L            at most L decomposition levels per axis (default 16; fewer on\n"
    "                        short axes, so that padding stays under 1/32 of the axis)\n"
    "  --lossless            every sample exact (integer samples; the default)\n"
    "  --max-error D         every sample within D of the input (integer samples)\n"
    "  --bound-route R       how --lossless and --max-error are met: residual (wavelet bands\n"
    "                        and a residual layer: every prefix is an approximation),\n"
    "                        predictive (no decomposition, neighbour prediction: often\n"
    "                        smaller, not progressive) or auto (the smaller; default)\n"
    "  --prediction P        how the coarsest block (all samples with the predictive route)\n"
    "                        is predicted: neighbour (MED / Lorenzo), weighted (spec 5.7.5;\n"
    "                        range coding only) or auto (the smaller; default)\n"
    "  --bits-per-sample R   the best quality within R bits per sample\n"
    "  --psnr P              the smallest stream with PSNR >= P dB (peak: max - min)\n"
    "                        (both: 1 and 2 levels are tried beside the most levels, and\n"
    "                        for integer samples the predictive route, which is not\n"
    "                        progressive; the best is kept)\n"
    "  --progressive         the most levels --levels allows, every prefix a coarser\n"
    "                        approximation (never fewer levels or the predictive route)\n"
    "  --step S              quantiser step S in sample units (no rate control)\n"
    "  --keep F              global oracle: keep the fraction F (0 < F <= 1) of the\n"
    "                        coefficients that contribute most to the L2 norm\n"
    "\n"
    "Region of interest (local oracle; with --step, --bits-per-sample, --psnr or --keep):\n"
    "  --roi box:X0,Y0[,Z0],X1,Y1[,Z1] | ellipsoid:CX,CY[,CZ],RX,RY[,RZ]\n"
    "                        in sample coordinates; every basis function reaching into\n"
    "                        the region keeps its detail, with a step --roi-gain times finer\n"
    "  --roi-falloff S       Gaussian falloff outside the region, in samples (default 16)\n"
    "  --roi-gain G          how much finer the step is inside the region (default 8)\n"
    "\n"
    "Metadata (the meta chunk, spec 2.6):\n"
    "  --meta KEY=VALUE      add an entry; repeatable. Registered keys: value_units,\n"
    "                        spatial_units, spacing, origin, crs, provenance, description\n"
    "\n"
    "Other:\n"
    "  --tile N[,N[,N]]      cut the grid into tiles of N samples per axis (one N for every\n"
    "                        axis, or one per axis; spec 11): each tile is coded and decoded\n"
    "                        on its own, and 'mrsv decode --region' reads only the tiles a\n"
    "                        box touches. 256 (2-D) or 64 (3-D) is a good size. A rate or PSNR\n"
    "                        target holds for the whole grid (one step for all tiles), an\n"
    "                        error bound for every sample. Not with --roi\n"
    "  --precinct N          code every band in blocks apart, each within a precinct of N\n"
    "                        samples per axis (a power of two, 16 to 2^24; spec 5.7.6): one\n"
    "                        transform of the whole grid, so that lossy coding loses less than\n"
    "                        with tiles, and a box is decoded from the blocks that reach it.\n"
    "                        256 (2-D) or 64 (3-D) is a good size. Not with --tile\n"
    "  --out-of-core         with --tile and a raw IN: read IN a row of tiles at a time and\n"
    "                        keep the coded tiles in a temporary file, so that the memory is\n"
    "                        a row of tiles, not the grid; the same stream as without it.\n"
    "                        A --bits-per-sample or --psnr target reads IN once per step\n"
    "                        tried (about 10 to 20 times). With --precinct and a raw IN: read\n"
    "                        IN a strip of precincts at a time, analyse level by level over\n"
    "                        strips and keep the coded blocks in temporary files, so that the\n"
    "                        memory is a few strips of the grid's width (CDF 9/7; a --step,\n"
    "                        --max-error, --lossless or --bits-per-sample, the last reading IN\n"
    "                        once per step tried; voids filled within each precinct)\n"
    "  --threads N           tiles (or precinct blocks) coded at once (default: the number of cores); the output\n"
    "                        is the same whatever N\n"
    "  --quiet               no progress output\n"
    "  --help                this text\n"
    "\n"
    "OUT is written under a temporary name and renamed when complete; IN is never touched.\n"
    "Exit status: 0 done, 1 invalid input data, 2 usage error, 3 file error.\n";

// "box:X0,Y0[,Z0],X1,Y1[,Z1]" or "ellipsoid:CX,CY[,CZ],RX,RY[,RZ]".
bool parseRegion(const std::string& text, RegionOfInterest* roi, std::string* error) {
  size_t colon = text.find(':');
  std::string shape = text.substr(0, colon);
  if (colon == std::string::npos || (shape != "box" && shape != "ellipsoid")) {
    *error = "'" + text + "' must start with box: or ellipsoid:";
    return false;
  }
  std::vector<double> v;
  std::string rest = text.substr(colon + 1);
  for (size_t start = 0; start <= rest.size();) {
    size_t comma = rest.find(',', start);
    if (comma == std::string::npos) comma = rest.size();
    std::string item = rest.substr(start, comma - start);
    char* end = nullptr;
    double x = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(x)) {
      *error = "'" + item + "' is not a number";
      return false;
    }
    v.push_back(x);
    start = comma + 1;
  }
  if (v.size() != 4 && v.size() != 6) {
    *error = "give 2 or 3 coordinates for each of the two corners (box) or centre and semi-axes";
    return false;
  }
  size_t dims = v.size() / 2;
  roi->ellipsoid = shape == "ellipsoid";
  for (size_t a = 0; a < dims; ++a) {
    if (roi->ellipsoid) {
      roi->center[a] = v[a];
      roi->half_size[a] = v[dims + a];
      if (!(roi->half_size[a] > 0)) {
        *error = "semi-axes must be positive";
        return false;
      }
    } else {
      double lo = std::min(v[a], v[dims + a]), hi = std::max(v[a], v[dims + a]);
      roi->center[a] = 0.5 * (lo + hi);
      roi->half_size[a] = 0.5 * (hi - lo);
    }
  }
  return true;
}

}  // namespace

int runEncode(int argc, char** argv) {
  if (isTetEncode(argc, argv)) return runTetEncode(argc, argv);
  if (isMeshEncode(argc, argv)) return runMeshEncode(argc, argv);
  const char* cmd = "encode";
  Args args;
  std::string error;
  if (!args.parse(argc, argv,
                  {{"dims", "type", "endian", "band", "nodata", "coding", "order", "levels", "max-error",
                    "bits-per-sample", "psnr", "step", "keep", "roi", "roi-falloff", "roi-gain", "bound-route", "entropy",
                    "wavelet", "prediction", "tile", "precinct", "threads"},
                   {"quiet", "help", "lossless", "progressive", "out-of-core"},
                   {"meta"}},
                  &error))
    return fail(cmd, error + " (see 'mrsv encode --help')", kExitUsage);
  if (args.flag("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  if (args.positional().size() != 2)
    return fail(cmd, "expected IN and OUT.mrsv (see 'mrsv encode --help')", kExitUsage);
  const std::string& in = args.positional()[0];
  const std::string& out = args.positional()[1];
  RawLayout raw;
  if (args.has("dims") != args.has("type"))
    return fail(cmd, "--dims and --type go together (see 'mrsv encode --help')", kExitUsage);
  if (args.has("dims")) {
    if (gridFormatOf(in) != GridFormat::kRaw)
      return fail(cmd, "--dims and --type are for headerless raw input; " + in + " has a header",
                  kExitUsage);
    raw.has_layout = true;
    if (std::string problem = parseDims(args.value("dims"), &raw.header); !problem.empty())
      return fail(cmd, "--dims: " + problem, kExitUsage);
    if (!parseSampleType(args.value("type"), &raw.header.sample_type))
      return fail(cmd, "--type '" + args.value("type") +
                           "' is not one of uint8, int16, uint16, int32, float32, float64",
                  kExitUsage);
    if (std::string problem = gridHeaderProblem(raw.header); !problem.empty())
      return fail(cmd, "--dims: " + problem, kExitUsage);
  } else if (gridFormatOf(in) == GridFormat::kRaw && !gridFormatsHaveGdal()) {
    // With GDAL, readGridInput offers the file to GDAL first and says both.
    return fail(cmd, "headerless raw input needs --dims and --type (see 'mrsv encode --help')",
                kExitUsage);
  }
  if (args.has("band")) {
    uint64_t band = 0;
    if (args.has("dims") || !parseUint64(args.value("band"), &band) || band < 1 || band > 65535)
      return fail(cmd, "--band takes a band number from 1, for rasters read through GDAL", kExitUsage);
    raw.band = static_cast<int>(band);
  }
  if (args.has("endian")) {
    if (args.value("endian") == "big") raw.big_endian = true;
    else if (args.value("endian") != "little")
      return fail(cmd, "--endian must be little or big", kExitUsage);
  }
  const std::string coding = args.has("coding") ? args.value("coding") : "wavelet";
  if (coding != "stored" && coding != "wavelet")
    return fail(cmd, "--coding '" + coding + "' is not one of wavelet, stored", kExitUsage);
  WaveletEncodeOptions wavelet;
  int targets = 0;
  auto number = [&](const char* name, double lo, double hi, double* out) -> bool {
    if (!args.has(name)) return true;
    char* end = nullptr;
    double v = std::strtod(args.value(name).c_str(), &end);
    if (args.value(name).empty() || *end != '\0' || !(v >= lo && v <= hi)) {
      error = std::string("--") + name + " '" + args.value(name) + "' must be a number from " +
              std::to_string(lo) + " to " + std::to_string(hi);
      return false;
    }
    *out = v;
    ++targets;
    return true;
  };
  double order = 2, levels = 16;
  if (!number("max-error", 0, 524287, &wavelet.max_error) ||
      !number("bits-per-sample", 1e-3, 64, &wavelet.bits_per_sample) ||
      !number("psnr", 1, 400, &wavelet.psnr) || !number("step", 1e-12, 1e300, &wavelet.step) ||
      !number("keep", 1e-9, 1, &wavelet.keep_fraction))
    return fail(cmd, error, kExitUsage);
  if (args.flag("lossless")) {
    wavelet.max_error = 0;
    ++targets;
  }
  if (targets > 1)
    return fail(cmd,
                "give at most one of --lossless, --max-error, --bits-per-sample, --psnr, --step, --keep",
                kExitUsage);
  if (targets == 0) wavelet.max_error = 0;  // lossless by default
  int rate_targets = targets;
  if (!number("order", 1, 4, &order) || !number("levels", 0, 16, &levels) ||
      !number("roi-falloff", 0, 1e9, &wavelet.roi.falloff) ||
      !number("roi-gain", 1, 1e6, &wavelet.roi_gain))
    return fail(cmd, error, kExitUsage);
  targets = rate_targets;
  if (args.has("entropy")) {
    if (args.value("entropy") == "baseline") wavelet.entropy_mode = kEntropyBaseline;
    else if (args.value("entropy") != "adaptive")
      return fail(cmd, "--entropy must be adaptive or baseline", kExitUsage);
  }
  if (args.has("prediction")) {
    const std::string& p = args.value("prediction");
    if (p == "neighbour") wavelet.prediction = WaveletEncodeOptions::Prediction::kNeighbour;
    else if (p == "weighted") wavelet.prediction = WaveletEncodeOptions::Prediction::kWeighted;
    else if (p != "auto") return fail(cmd, "--prediction must be auto, neighbour or weighted", kExitUsage);
    if (wavelet.prediction == WaveletEncodeOptions::Prediction::kWeighted &&
        wavelet.entropy_mode == kEntropyBaseline)
      return fail(cmd, "--prediction weighted needs --entropy adaptive", kExitUsage);
  }
  if (args.has("bound-route")) {
    const std::string& r = args.value("bound-route");
    if (r == "residual") wavelet.bound_route = WaveletEncodeOptions::BoundRoute::kResidual;
    else if (r == "predictive") wavelet.bound_route = WaveletEncodeOptions::BoundRoute::kPredictive;
    else if (r != "auto") return fail(cmd, "--bound-route must be auto, residual or predictive", kExitUsage);
    if (wavelet.max_error < 0)
      return fail(cmd, "--bound-route goes with --lossless or --max-error", kExitUsage);
    if (wavelet.bound_route == WaveletEncodeOptions::BoundRoute::kPredictive && args.flag("progressive"))
      return fail(cmd, "--bound-route predictive is not progressive; drop one of them", kExitUsage);
  }
  wavelet.progressive = args.flag("progressive");
  if (args.has("roi")) {
    if (!parseRegion(args.value("roi"), &wavelet.roi, &error)) return fail(cmd, "--roi: " + error, kExitUsage);
    if (wavelet.max_error >= 0)
      return fail(cmd, "--roi goes with --step, --bits-per-sample, --psnr or --keep (lossless and "
                       "error-bounded coding are exact everywhere)", kExitUsage);
    wavelet.has_roi = true;
  }
  if (order != std::floor(order) || levels != std::floor(levels))
    return fail(cmd, "--order and --levels take whole numbers", kExitUsage);
  // The wavelet: CDF 9/7 unless B-splines are asked for, by name or by order.
  const std::string family = args.has("wavelet") ? args.value("wavelet") : args.has("order") ? "bspline" : "cdf97";
  if (family == "cdf97") {
    if (args.has("order")) return fail(cmd, "--order is for --wavelet bspline", kExitUsage);
    wavelet.order = kWaveletOrderCdf97;
  } else if (family == "bspline") {
    wavelet.order = static_cast<int>(order);
  } else {
    return fail(cmd, "--wavelet must be bspline or cdf97", kExitUsage);
  }
  wavelet.max_levels = static_cast<int>(levels);
  if (coding == "stored" && (args.has("order") || args.has("levels") || args.has("max-error") ||
                             args.has("bits-per-sample") || args.has("psnr") || args.has("step")))
    return fail(cmd, "--coding stored takes no rate, quality or wavelet option", kExitUsage);
  if (args.has("precinct")) {
    if (coding == "stored") return fail(cmd, "--precinct needs --coding wavelet", kExitUsage);
    if (args.has("tile")) return fail(cmd, "--precinct and --tile are two ways to cut a grid; give one", kExitUsage);
    const std::string& text = args.value("precinct");
    int log2 = -1;
    for (int p = kMinPrecinctLog2; p <= kMaxPrecinctLog2; ++p)
      if (text == std::to_string(1u << p)) log2 = p;
    if (log2 < 0)
      return fail(cmd, "--precinct '" + text + "': must be a power of two from " +
                           std::to_string(1u << kMinPrecinctLog2) + " to " +
                           std::to_string(1u << kMaxPrecinctLog2), kExitUsage);
    wavelet.precinct_log2 = log2;
  }
  std::vector<uint32_t> tile_sizes;
  if (args.has("tile")) {
    if (coding == "stored") return fail(cmd, "--tile needs --coding wavelet", kExitUsage);
    const std::string& text = args.value("tile");
    std::vector<uint64_t> sizes;
    if (!parseWholeNumberList(text, 1, kMaxGridAxis, &sizes))
      return fail(cmd, "--tile '" + text + "': each size must be a whole number from 1 to " +
                           std::to_string(kMaxGridAxis), kExitUsage);
    tile_sizes.assign(sizes.begin(), sizes.end());
    if (tile_sizes.size() > 3) return fail(cmd, "--tile takes at most 3 sizes", kExitUsage);
  }
  TiledEncodeOptions tiled;
  tiled.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (args.has("threads")) {
    uint64_t threads = 0;
    if (!parseUint64(args.value("threads"), &threads) || threads < 1 || threads > 1024)
      return fail(cmd, "--threads must be a whole number from 1 to 1024", kExitUsage);
    tiled.threads = static_cast<int>(threads);
  }
  Metadata metadata;
  if (!parseMetaOptions(args, &metadata, &error)) return fail(cmd, error, kExitUsage);
  if (isSameFile(in, out)) return fail(cmd, "OUT is the same file as IN; refusing to overwrite the input", kExitUsage);
  if (args.flag("out-of-core")) {
    const bool precincts = wavelet.precinct_log2 > 0;
    if ((tile_sizes.empty() && !precincts) || !raw.has_layout)
      return fail(cmd, "--out-of-core needs --tile or --precinct and a headerless raw IN (--dims, --type)",
                  kExitUsage);
    if (args.has("roi"))
      return fail(cmd, "--out-of-core does not take --roi in this version", kExitUsage);
    GridHeader header = raw.header;
    if (args.has("nodata")) {
      if (!parseNodata(args.value("nodata"), header.sample_type, &header.nodata_bits, &error))
        return fail(cmd, error, kExitUsage);
      header.grid_flags |= kGridFlagHasNodata;
    }
    for (int a = 0; a < 3 && !precincts; ++a)
      tiled.tile_size[a] = a >= header.num_dims ? 1 : tile_sizes[std::min<size_t>(a, tile_sizes.size() - 1)];
    std::unique_ptr<GridBoxReader> reader =
        openRawBoxReader(in, header, raw.big_endian ? Endian::kBig : Endian::kLittle, &error);
    if (!reader) return fail(cmd, error, kExitIo);
    Progress progress("encode", args.flag("quiet"));
    tiled.progress = [&](uint64_t done, uint64_t total) {
      progress.update(static_cast<double>(done) / static_cast<double>(total));
    };
    AtomicFileWriter sink;
    if (!sink.open(out, &error)) return fail(cmd, out + ": " + error, kExitIo);
    WaveletEncodeReport report;
    PrecinctStreamOptions run;
    run.threads = tiled.threads;
    run.progress = [&](double done) { progress.update(done); };
    if (Error e = precincts ? encodePrecinctGridFromReader(header, *reader, metadata, wavelet, run, sink, &report)
                            : encodeTiledGridFromReader(header, *reader, metadata, wavelet, tiled, sink, &report);
        !e.ok())
      return fail(cmd, in + ": " + e.field + ": " + e.message,
                  e.status == Status::kIoError ? kExitIo : kExitInvalidData);
    if (!sink.commit(&error)) return fail(cmd, out + ": " + error, kExitIo);
    if (!args.flag("quiet"))
      std::fprintf(stderr, "mrsv encode: %s: %llu bytes, %.4f bits/sample, PSNR %s dB, max error %g (out of core)\n",
                   out.c_str(), static_cast<unsigned long long>(report.bytes), report.bits_per_sample,
                   std::isinf(report.psnr) ? "inf" : std::to_string(report.psnr).c_str(), report.max_abs_error);
    return kExitOk;
  }

  Progress progress("encode", args.flag("quiet"));
  GridInput input;
  if (!readGridInput(in, raw, &input, &error)) {
    bool io = error.find("No such file") != std::string::npos ||
              error.find("Permission denied") != std::string::npos ||
              error.find("directory") != std::string::npos;
    return fail(cmd, error, io ? kExitIo : kExitInvalidData);
  }
  progress.update(0.2);
  GridHeader& header = input.header;
  const std::vector<uint8_t>& samples = input.samples;
  if (args.has("nodata")) {
    if (!parseNodata(args.value("nodata"), header.sample_type, &header.nodata_bits, &error))
      return fail(cmd, error, kExitUsage);
    header.grid_flags |= kGridFlagHasNodata;
  }
  // What the file says first, then --meta (which wins).
  Metadata merged = input.metadata;
  for (const auto& [key, value] : metadata.entries) merged.set(key, value);
  metadata = merged;
  std::vector<uint8_t> stream;
  WaveletEncodeReport report;
  Error e;
  if (coding == "stored") {
    e = encodeStoredGrid(header, samples, metadata, &stream);
  } else if (!tile_sizes.empty()) {
    if (tile_sizes.size() != 1 && tile_sizes.size() != header.num_dims)
      return fail(cmd, "--tile gives " + std::to_string(tile_sizes.size()) + " sizes for a grid of " +
                           std::to_string(header.num_dims) + " dimensions (give 1 or " +
                           std::to_string(header.num_dims) + ")", kExitUsage);
    for (int a = 0; a < 3; ++a)
      tiled.tile_size[a] = a >= header.num_dims ? 1 : tile_sizes[std::min<size_t>(a, tile_sizes.size() - 1)];
    tiled.progress = [&](uint64_t done, uint64_t total) {
      progress.update(0.2 + 0.7 * static_cast<double>(done) / static_cast<double>(total));
    };
    e = encodeTiledGrid(header, samples, metadata, wavelet, tiled, &stream, &report);
  } else {
    e = encodeWaveletGrid(header, samples, metadata, wavelet, &stream, &report);
  }
  if (!e.ok()) return fail(cmd, in + ": " + e.field + ": " + e.message, kExitInvalidData);
  progress.update(0.9);
  if (!writeFileAtomically(out, stream, &error)) return fail(cmd, out + ": " + error, kExitIo);
  if (coding == "wavelet" && !args.flag("quiet") && !tile_sizes.empty()) {
    const std::string levels = report.levels > 0 ? "up to " + std::to_string(report.levels) + " levels per tile"
                                                 : "levels 0 in every tile (predictive route, not progressive)";
    std::fprintf(stderr, "mrsv encode: %s: %llu bytes, %.4f bits/sample, PSNR %s dB, max error %g, tiled, %s\n",
                 out.c_str(), static_cast<unsigned long long>(report.bytes), report.bits_per_sample,
                 std::isinf(report.psnr) ? "inf" : std::to_string(report.psnr).c_str(), report.max_abs_error,
                 levels.c_str());
  } else if (coding == "wavelet" && !args.flag("quiet")) {
    std::fprintf(stderr,
                 "mrsv encode: %s: %llu bytes, %.4f bits/sample, PSNR %s dB, max error %g, "
                 "%s, %llu coefficients kept, L2 error %.6g (orthogonal estimate %.6g)\n",
                 out.c_str(), static_cast<unsigned long long>(report.bytes), report.bits_per_sample,
                 std::isinf(report.psnr) ? "inf" : std::to_string(report.psnr).c_str(),
                 report.max_abs_error,
                 report.levels > 0 ? ("levels " + std::to_string(report.levels)).c_str()
                                   : "levels 0 (predictive route, not progressive)",
                 static_cast<unsigned long long>(report.kept_coefficients),
                 report.l2_error, report.l2_error_orthogonal_estimate);
  }
  progress.update(1.0);
  return kExitOk;
}

}  // namespace mrsv::cli
