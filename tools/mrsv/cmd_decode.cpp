// mrsv decode: an MRSV file (or a prefix of one) to raw samples.
#include <algorithm>
#include <cstdio>
#include <thread>
#include <utility>

#include "cli.h"
#include "commands.h"
#include "mrsv/file_io.h"
#include "mrsv/grid_formats.h"
#include "mrsv/grid.h"
#include "mrsv/progressive_mesh.h"
#include "mrsv/progressive_tet_mesh.h"
#include "mrsv/raw_grid.h"

namespace mrsv::cli {
namespace {

const char kHelp[] =
    "Usage: mrsv decode [options] IN.mrsv OUT\n"
    "\n"
    "A PM stream (spec 6) decodes to a mesh: OUT.obj, OUT.ply (binary) or OUT.off, at the\n"
    "level chosen by one of:\n"
    "  --faces N             the finest level with at most N triangles\n"
    "  --vertices N          the level with N vertices (base..full)\n"
    "  --fraction F          the finest level with at most F times the full triangle count\n"
    "(default: every split decoded; --canonical writes spec 6.8's canonical mesh output).\n"
    "\n"
    "A PT stream (spec 7) decodes to a tet mesh: OUT.vtu (VTK XML), OUT.vtk (legacy),\n"
    "OUT.mesh (MEDIT) or OUT.node (TetGen, with OUT.ele), fields as point data, at the\n"
    "level chosen by one of:\n"
    "  --tets N              the finest level with at most N tets\n"
    "  --vertices N          the level with N vertices (base..full)\n"
    "  --fraction F          the finest level with at most F times the full tet count\n"
    "(default: every split decoded; --canonical writes spec 7.8's canonical output).\n"
    "\n"
    "Decode an MRSV grid. OUT is chosen by its extension: .nrrd (with a header),\n"
    "  .pgm (2-D uint8 or uint16), .tif/.tiff (a GeoTIFF of a 1-D or 2-D grid, through\n"
    "  GDAL, georeferenced from the meta chunk's origin, spacing and crs, with its no-data\n"
    "  value; at --levels K the spacing is the coarser one), or else a headerless raw file\n"
    "  of the stream's sample type (x fastest, then y, then z).\n"
    "\n"
    "Options:\n"
    "  --endian little|big   byte order of OUT (default little)\n"
    "  --canonical           write the canonical output of spec 3.4 instead: the bytes\n"
    "                        whose SHA-256 the conformance suite compares\n"
    "  --levels K            reduced resolution: stop the wavelet synthesis K levels above\n"
    "                        the finest (about 1/2^K of the samples along each axis)\n"
    "  --region X0,Y0[,Z0],X1,Y1[,Z1]\n"
    "                        decode only the box X0 <= x < X1, Y0 <= y < Y1 (Z0 <= z < Z1) of\n"
    "                        samples; from a tiled stream (encode --tile) only the tiles the\n"
    "                        box touches are read (spec 11.5). With --levels K, the samples\n"
    "                        of the box on the lattice of every 2^K-th sample\n"
    "  --threads N           tiles decoded at once (default: the number of cores)\n"
    "  --bytes N             read only the first N bytes of IN, as if the rest had not\n"
    "                        arrived: the complete chunks among them are decoded\n"
    "  --quiet               no progress or notes on stderr\n"
    "  --help                this text\n"
    "\n"
    "A file that ends after a complete chunk but before MEND is a prefix and decodes\n"
    "to what its complete chunks hold. OUT is written under a temporary name and renamed\n"
    "when complete. Exit status: 0 done, 1 invalid stream, 2 usage error, 3 file error.\n";

// "X0,Y0[,Z0],X1,Y1[,Z1]": a half-open box of samples.
bool parseRegionBox(const std::string& text, GridRegion* region, std::string* error) {
  std::vector<uint64_t> v;
  for (size_t start = 0; start <= text.size();) {
    size_t comma = std::min(text.find(',', start), text.size());
    uint64_t x = 0;
    if (!parseUint64(text.substr(start, comma - start), &x) || x > kMaxGridAxis) {
      *error = "--region '" + text + "': each coordinate must be a whole number from 0 to " +
               std::to_string(kMaxGridAxis);
      return false;
    }
    v.push_back(x);
    start = comma + 1;
  }
  if (v.size() != 2 && v.size() != 4 && v.size() != 6) {
    *error = "--region '" + text + "': give X0,X1 or X0,Y0,X1,Y1 or X0,Y0,Z0,X1,Y1,Z1";
    return false;
  }
  const size_t dims = v.size() / 2;
  for (size_t a = 0; a < dims; ++a) {
    region->lo[a] = static_cast<uint32_t>(v[a]);
    region->hi[a] = static_cast<uint32_t>(v[dims + a]);
  }
  return true;
}

}  // namespace

int runDecode(int argc, char** argv) {
  const char* cmd = "decode";
  Args args;
  std::string error;
  if (!args.parse(argc, argv, {{"endian", "bytes", "levels", "faces", "tets", "vertices", "fraction", "region", "threads"}, {"canonical", "quiet", "help"}, {}}, &error))
    return fail(cmd, error + " (see 'mrsv decode --help')", kExitUsage);
  if (args.flag("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  if (args.positional().size() != 2)
    return fail(cmd, "expected IN.mrsv and OUT (see 'mrsv decode --help')", kExitUsage);
  const std::string& in = args.positional()[0];
  const std::string& out = args.positional()[1];
  Endian endian = Endian::kLittle;
  if (args.has("endian")) {
    if (args.value("endian") == "big") endian = Endian::kBig;
    else if (args.value("endian") != "little")
      return fail(cmd, "--endian must be little or big", kExitUsage);
  }
  uint64_t byte_limit = UINT64_MAX;
  if (args.has("bytes") && !parseUint64(args.value("bytes"), &byte_limit))
    return fail(cmd, "--bytes '" + args.value("bytes") + "' is not a whole number", kExitUsage);
  uint64_t levels = 0;
  if (args.has("levels") && (!parseUint64(args.value("levels"), &levels) || levels > 16))
    return fail(cmd, "--levels '" + args.value("levels") + "' is not a whole number from 0 to 16",
                kExitUsage);
  if (isSameFile(in, out)) return fail(cmd, "OUT is the same file as IN; refusing to overwrite the input", kExitUsage);
  GridRegion region;
  const bool by_region = args.has("region");
  if (by_region && !parseRegionBox(args.value("region"), &region, &error)) return fail(cmd, error, kExitUsage);
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (args.has("threads")) {
    uint64_t n = 0;
    if (!parseUint64(args.value("threads"), &n) || n < 1 || n > 1024)
      return fail(cmd, "--threads must be a whole number from 1 to 1024", kExitUsage);
    threads = static_cast<int>(n);
  }
  if (by_region && !args.has("bytes")) return runRegionDecode(args, in, out, region, threads, endian, levels);

  Progress progress("decode", args.flag("quiet"));
  std::vector<uint8_t> bytes;
  if (!readWholeFile(in, &bytes, &error)) return fail(cmd, in + ": " + error, kExitIo);
  DecodeOptions options;
  options.reduce_levels = static_cast<int>(levels);
  options.threads = threads;
  if (byte_limit < bytes.size()) {
    bytes.resize(static_cast<size_t>(byte_limit));
    options.container.allow_partial_tail = true;
  }
  if (isProgressiveMeshStream(bytes.data(), bytes.size())) return runMeshDecode(args, in, out, bytes, options);
  if (isProgressiveTetStream(bytes.data(), bytes.size())) return runTetDecode(args, in, out, bytes, options);
  if (args.has("faces") || args.has("tets") || args.has("vertices") || args.has("fraction"))
    return fail(cmd, in + ": --faces, --tets, --vertices and --fraction are for mesh streams; this is a grid",
                kExitUsage);
  if (levels > 0 && args.flag("canonical"))
    return fail(cmd, "--canonical is defined at full resolution only", kExitUsage);
  if (by_region) {
    MemoryByteSource source(bytes.data(), bytes.size());
    return runRegionDecode(args, in, out, region, threads, endian, levels, &source);
  }
  progress.update(0.2);
  DecodedGrid grid;
  if (Error e = decodeGrid(bytes.data(), bytes.size(), options, &grid); !e.ok())
    return reportError(cmd, in, e);
  progress.update(0.8);

  std::vector<uint8_t> output;
  if (args.flag("canonical")) {
    output = canonicalGridOutput(grid);
  } else {
    if (!grid.has_samples)
      return fail(cmd, in + ": the stream ends before its sample data (a prefix of " +
                           std::to_string(grid.container.chunks.size()) + " chunks)",
                  kExitInvalidData);
    // A tiled grid reduced by K takes every 2^K-th sample on every axis (spec 11.6).
    static const uint8_t kEveryAxis[3] = {16, 16, 16};
    const Metadata metadata = reducedResolutionMetadata(
        grid.metadata, grid.header,
        grid.header.coding == GridCoding::kTiled ? kEveryAxis : grid.wavelet.levels, options.reduce_levels);
    if (!encodeGridOutput(out, grid.header, metadata, grid.output_size, std::move(grid.samples),
                          endian == Endian::kBig, &output, &error))
      return fail(cmd, error, kExitUsage);
  }
  if (!args.flag("quiet") && !args.flag("canonical") &&
      (grid.output_size[0] != grid.header.size_x || grid.output_size[1] != grid.header.size_y ||
       grid.output_size[2] != grid.header.size_z))
    std::fprintf(stderr, "mrsv decode: %s: reduced resolution %ux%ux%u\n", out.c_str(),
                 grid.output_size[0], grid.output_size[1], grid.output_size[2]);
  if (!grid.container.complete && !args.flag("quiet"))
    std::fprintf(stderr, "mrsv decode: %s: note: stream is a prefix (no MEND); decoded its %zu complete chunks\n",
                 in.c_str(), grid.container.chunks.size());
  if (!writeFileAtomically(out, output, &error)) return fail(cmd, out + ": " + error, kExitIo);
  progress.update(1.0);
  return kExitOk;
}

}  // namespace mrsv::cli
