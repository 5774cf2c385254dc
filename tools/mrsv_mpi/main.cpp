// mrsv-mpi: tiled grids (spec 11) and grids in precincts (5.7.6) encoded and
// decoded by MPI ranks.
//
//   mpirun -np N mrsv-mpi encode --dims X,Y[,Z] --type T --tile S [options] IN.raw OUT.mrsv
//   mpirun -np N mrsv-mpi encode --dims X,Y[,Z] --type T --precinct S [options] IN.raw OUT.mrsv
//   mpirun -np N mrsv-mpi decode IN.mrsv OUT.raw
//
// encode --tile: each rank reads its rows of tiles from the raw file, codes
// them, and the ranks agree on the index (every tile's chunk lengths,
// gathered) and the error figures; then each writes its chunks at their
// offsets with MPI-IO into one file. The stream is byte-identical to 'mrsv
// encode --tile' of the same input with the same options, whatever the
// number of ranks.
// encode --precinct: the out-of-core precinct encoder run by the ranks as a
// team (decision D92: pieces, boxes and blocks dealt round-robin, the
// low-pass parts shared through MPI-IO scratch files); byte-identical to
// 'mrsv encode --precinct --out-of-core'.
// decode: each rank decodes a band of rows by region (through the tile index,
// or by precinct) and writes it at its place in the raw output with MPI-IO.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "cli.h"
#include "heap_tuning.h"
#include "mpi_team.h"
#include "mrsv/encode.h"
#include "mrsv/file_io.h"
#include "mrsv/raw_grid.h"
#include "mrsv/tiled_grid.h"
#include "tiles/tile_encoding.h"

namespace mrsv::mpi {
namespace {

using cli::Args;

const char kHelp[] =
    "Usage: mpirun -np N mrsv-mpi encode [options] IN.raw OUT.mrsv\n"
    "       mpirun -np N mrsv-mpi decode IN.mrsv OUT.raw\n"
    "\n"
    "Tiled grids (spec 11) and grids in precincts (5.7.6) coded and decoded by MPI ranks,\n"
    "each working on its own part and writing it into one file with MPI-IO. The stream is\n"
    "byte-identical to 'mrsv encode --tile' (or 'mrsv encode --precinct --out-of-core') of\n"
    "the same input and options, whatever the number of ranks.\n"
    "\n"
    "encode options:\n"
    "  --dims X[,Y[,Z]]      grid size in samples (IN is headerless raw, x fastest)\n"
    "  --type T              uint8, int16, uint16, int32, float32, float64\n"
    "  --endian little|big   byte order of IN (default little)\n"
    "  --nodata V            sample value that marks missing data\n"
    "  --tile N[,N[,N]]      tile size; or\n"
    "  --precinct N          precincts of N samples per axis (a power of two, 16 or more),\n"
    "                        coded out of core by the ranks together (2-D and 3-D grids)\n"
    "  --lossless            every sample exact (the default)\n"
    "  --max-error D         every sample within D (integer samples)\n"
    "  --bound-route R       residual, predictive or auto (default): as mrsv encode (--tile)\n"
    "  --step S              quantiser step S in sample units\n"
    "  --bits-per-sample B   the finest step whose stream fits B bits per sample (--precinct)\n"
    "  --scratch DIR         --precinct: where the ranks share their temporary files (a\n"
    "                        directory every rank sees; default: the directory of OUT)\n"
    "  --levels L            at most L decomposition levels per axis\n"
    "  --progressive         the most levels --levels allows in every tile\n"
    "  --threads N           threads per rank (default 1)\n"
    "  --meta KEY=VALUE      a meta entry; repeatable\n"
    "\n"
    "decode: OUT.raw receives the samples, little-endian, x fastest.\n"
    "The last line on stderr ends with the seconds since every rank started (without MPI\n"
    "start-up).\n"
    "Exit status: 0 done, 1 invalid input, 2 usage error, 3 file error.\n";

int rank = 0, ranks = 1;
bool serialized = false;  // MPI takes calls from any thread, one at a time (--threads above 1)
// MPI_Wtime() once every rank has started: the status lines give the time
// from there, the ranks' own work, without the launcher's and MPI_Init's
// start-up (a fixed 0.1 to 0.4 s that would hide the speed-up of small jobs).
double started = 0;

double elapsed() { return MPI_Wtime() - started; }

// Every rank agrees on failure: the first rank's message (by rank number)
// is printed once, by that rank, and every rank returns the same status.
int agree(int status, const std::string& message) {
  int worst = 0;
  MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (worst == 0) return 0;
  int mine = status != 0 ? rank : ranks, first = ranks;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (rank == first) std::fprintf(stderr, "mrsv-mpi: %s\n", message.c_str());
  return worst;
}

// MPI-IO to a temporary name beside `path`, renamed by rank 0 when every rank
// has written; removed when any has failed.
struct SharedFile {
  MPI_File file = MPI_FILE_NULL;
  std::string path, temp;
  bool open(const std::string& out) {
    path = out;
    temp = out + ".mrsv-mpi-tmp";
    if (rank == 0) std::remove(temp.c_str());
    MPI_Barrier(MPI_COMM_WORLD);
    return MPI_File_open(MPI_COMM_WORLD, temp.c_str(), MPI_MODE_CREATE | MPI_MODE_WRONLY, MPI_INFO_NULL, &file) ==
           MPI_SUCCESS;
  }
  bool writeAt(uint64_t offset, const uint8_t* data, uint64_t size) {
    while (size > 0) {
      const int n = static_cast<int>(std::min<uint64_t>(size, 1u << 30));
      MPI_Status st;
      if (MPI_File_write_at(file, static_cast<MPI_Offset>(offset), data, n, MPI_BYTE, &st) != MPI_SUCCESS)
        return false;
      offset += n;
      data += n;
      size -= n;
    }
    return true;
  }
  // Collective: closes, then renames (status 0) or removes the file.
  int finish(int status) {
    if (file != MPI_FILE_NULL) MPI_File_close(&file);
    if (rank == 0) {
      if (status == 0 && std::rename(temp.c_str(), path.c_str()) != 0) status = cli::kExitIo;
      if (status != 0) std::remove(temp.c_str());
    }
    MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return status;
  }
};

// The out-of-core precinct encoder run by the ranks as one team; the stream
// goes to a temporary name beside OUT, renamed when complete.
int encodePrecincts(const GridHeader& header, GridBoxReader& reader, const Metadata& metadata,
                    const WaveletEncodeOptions& options, int threads, const std::string& in, const std::string& out,
                    const std::string& scratch) {
  MpiTeam team(scratch);
  const std::string temp = out + ".mrsv-mpi-tmp";
  if (rank == 0) std::remove(temp.c_str());
  MPI_Barrier(MPI_COMM_WORLD);
  Error e;
  std::unique_ptr<MpiFile> file = MpiFile::open(temp, false, &e);
  if (int s = agree(file ? 0 : cli::kExitIo, out + ": cannot create the output with MPI-IO")) return s;
  PrecinctStreamOptions run;
  run.threads = threads;
  WaveletEncodeReport report;
  // Every rank returns the same error: the team agreed on it.
  e = encodePrecinctGridAsTeam(header, reader, metadata, options, run, team, *file, &report);
  file->close();
  int status = e.ok() ? 0 : e.status == Status::kIoError ? cli::kExitIo : cli::kExitInvalidData;
  if (rank == 0) {
    if (status == 0 && std::rename(temp.c_str(), out.c_str()) != 0) {
      status = cli::kExitIo;
      e = Error{Status::kIoError, 0, "file", out + ": cannot rename the output into place"};
    }
    if (status != 0) {
      std::remove(temp.c_str());
      std::fprintf(stderr, "mrsv-mpi: %s: %s: %s\n", in.c_str(), e.field.c_str(), e.message.c_str());
    } else {
      std::fprintf(stderr, "mrsv-mpi encode: %s: %llu bytes, %.4f bits/sample, max error %g, %d ranks, %.3f s\n",
                   out.c_str(), static_cast<unsigned long long>(report.bytes), report.bits_per_sample,
                   report.max_abs_error, ranks, elapsed());
    }
  }
  MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return status;
}

int runEncode(int argc, char** argv) {
  Args args;
  std::string error;
  if (!args.parse(argc, argv,
                  {{"dims", "type", "endian", "nodata", "tile", "precinct", "max-error", "bound-route", "step",
                    "bits-per-sample", "levels", "threads", "scratch"},
                   {"lossless", "progressive", "help"},
                   {"meta"}},
                  &error))
    return agree(cli::kExitUsage, error);
  if (args.flag("help")) {
    if (rank == 0) std::fputs(kHelp, stdout);
    return 0;
  }
  if (args.positional().size() != 2 || !args.has("dims") || !args.has("type") ||
      args.has("tile") == args.has("precinct"))
    return agree(cli::kExitUsage,
                 "encode needs --dims, --type, one of --tile and --precinct, IN.raw and OUT.mrsv (see --help)");
  const std::string& in = args.positional()[0];
  const std::string& out = args.positional()[1];
  GridHeader header;
  if (std::string problem = parseDims(args.value("dims"), &header); !problem.empty())
    return agree(cli::kExitUsage, "--dims: " + problem);
  if (!parseSampleType(args.value("type"), &header.sample_type))
    return agree(cli::kExitUsage, "--type '" + args.value("type") + "' is not a sample type");
  if (args.has("nodata")) {
    if (!cli::parseNodata(args.value("nodata"), header.sample_type, &header.nodata_bits, &error))
      return agree(cli::kExitUsage, error);
    header.grid_flags |= kGridFlagHasNodata;
  }
  std::vector<uint64_t> sizes{1};
  if (args.has("tile") && (!cli::parseWholeNumberList(args.value("tile"), 1, kMaxGridAxis, &sizes) ||
                           (sizes.size() != 1 && sizes.size() != header.num_dims)))
    return agree(cli::kExitUsage, "--tile '" + args.value("tile") + "': give 1 size or one per axis, each from 1 to " +
                                      std::to_string(kMaxGridAxis));
  TiledEncodeOptions tiled;
  for (int a = 0; a < 3; ++a)
    tiled.tile_size[a] = a >= header.num_dims ? 1 : static_cast<uint32_t>(sizes[std::min<size_t>(a, sizes.size() - 1)]);
  tiled.threads = 1;
  uint64_t number = 0;
  if (args.has("threads")) {
    if (!cli::parseUint64(args.value("threads"), &number) || number < 1 || number > 1024)
      return agree(cli::kExitUsage, "--threads must be 1 to 1024");
    tiled.threads = static_cast<int>(number);
    if (tiled.threads > 1 && !serialized)
      return agree(cli::kExitUsage, "--threads above 1 needs an MPI library with MPI_THREAD_SERIALIZED");
  }
  WaveletEncodeOptions options;
  options.max_error = 0;
  if (args.has("max-error") && !cli::parseDouble(args.value("max-error"), &options.max_error))
    return agree(cli::kExitUsage, "--max-error is not a number");
  if (args.has("bound-route")) {
    const std::string& route = args.value("bound-route");
    if (route == "residual") options.bound_route = WaveletEncodeOptions::BoundRoute::kResidual;
    else if (route == "predictive") options.bound_route = WaveletEncodeOptions::BoundRoute::kPredictive;
    else if (route != "auto") return agree(cli::kExitUsage, "--bound-route must be residual, predictive or auto");
  }
  if (args.has("step")) {
    options.max_error = -1;
    if (!cli::parseDouble(args.value("step"), &options.step) || !(options.step > 0))
      return agree(cli::kExitUsage, "--step must be a positive number");
  }
  if (args.has("bits-per-sample")) {
    if (!args.has("precinct")) return agree(cli::kExitUsage, "--bits-per-sample goes with --precinct");
    options.max_error = -1;
    if (!cli::parseDouble(args.value("bits-per-sample"), &options.bits_per_sample) ||
        !(options.bits_per_sample >= 1e-3 && options.bits_per_sample <= 64))
      return agree(cli::kExitUsage, "--bits-per-sample must be a number from 0.001 to 64");
  }
  if (int(args.has("step")) + int(args.has("bits-per-sample")) + int(args.has("max-error")) +
          int(args.flag("lossless")) > 1)
    return agree(cli::kExitUsage, "give at most one of --lossless, --max-error, --step, --bits-per-sample");
  if (args.has("precinct")) {
    const std::string& text = args.value("precinct");
    for (int p = kMinPrecinctLog2; p <= kMaxPrecinctLog2; ++p)
      if (text == std::to_string(1u << p)) options.precinct_log2 = p;
    if (options.precinct_log2 == 0)
      return agree(cli::kExitUsage, "--precinct '" + text + "': must be a power of two from " +
                                        std::to_string(1u << kMinPrecinctLog2) + " to " +
                                        std::to_string(1u << kMaxPrecinctLog2));
  }
  if (args.has("levels")) {
    if (!cli::parseUint64(args.value("levels"), &number) || number > 16)
      return agree(cli::kExitUsage, "--levels must be 0 to 16");
    options.max_levels = static_cast<int>(number);
  }
  options.progressive = args.flag("progressive");
  Metadata metadata;
  if (!cli::parseMetaOptions(args, &metadata, &error)) return agree(cli::kExitUsage, error);
  TilingHeader tiling;
  std::copy(tiled.tile_size, tiled.tile_size + 3, tiling.tile_size);
  if (std::string problem = gridHeaderProblem(header); !problem.empty()) return agree(cli::kExitUsage, problem);
  if (args.has("tile"))
    if (std::string problem = tilingProblem(tiling, header); !problem.empty()) return agree(cli::kExitUsage, problem);
  if (isSameFile(in, out)) return agree(cli::kExitUsage, "OUT is the same file as IN; refusing to overwrite the input");
  std::unique_ptr<GridBoxReader> reader = openRawBoxReader(
      in, header, args.has("endian") && args.value("endian") == "big" ? Endian::kBig : Endian::kLittle, &error);
  if (int s = agree(reader ? 0 : cli::kExitIo, error)) return s;
  if (args.has("precinct")) {
    std::string scratch = args.has("scratch") ? args.value("scratch") : out.substr(0, out.find_last_of('/') + 1);
    if (scratch.empty()) scratch = ".";
    return encodePrecincts(header, *reader, metadata, options, tiled.threads, in, out, scratch);
  }

  // This rank's rows of tiles: row r (tiles along x) goes to rank r % ranks.
  GridHeader h = header;
  h.coding = GridCoding::kTiled;
  const TileGrid tiles = TileGrid::make(h, tiling);
  const uint64_t n = tiles.tileCount();
  const size_t bytes = sampleSize(h.sample_type);
  std::vector<TileResult> mine(n);
  ErrorTally local;
  int status = 0;
  for (uint64_t row = rank; row < uint64_t{tiles.count[1]} * tiles.count[2] && status == 0; row += ranks) {
    const uint64_t first = row * tiles.count[0];
    uint32_t origin[3], size[3];
    tiles.box(first, origin, size);
    origin[0] = 0;
    size[0] = h.size_x;
    std::vector<uint8_t> box(uint64_t{size[0]} * size[1] * size[2] * bytes);
    if (!reader->read(origin, size, box.data(), &error)) {
      status = cli::kExitIo;
      error = in + ": " + error;
      break;
    }
    local.addSamples(h, box.data(), box.size());
    for (uint64_t t = first; t < first + tiles.count[0]; ++t) {
      mine[t] = encodeTileSamples(tiles, t, tileSamplesFrom(tiles, t, box.data(), origin, size), options);
      if (!mine[t].error.ok()) {
        status = cli::kExitInvalidData;
        error = in + ": " + mine[t].error.field + ": " + mine[t].error.message;
        break;
      }
    }
  }
  if (int s = agree(status, error)) return s;

  // Every tile's chunk count, types, lengths and errors, on every rank (each
  // tile was coded by one rank: the others add zeros).
  std::vector<int> counts(n), all_counts(n);
  std::vector<double> sse(n), max_abs(n), levels(n);
  for (uint64_t t = 0; t < n; ++t) {
    counts[t] = static_cast<int>(mine[t].chunks.size());
    sse[t] = mine[t].sse;
    max_abs[t] = mine[t].max_abs;
    levels[t] = mine[t].levels;
  }
  MPI_Allreduce(counts.data(), all_counts.data(), static_cast<int>(n), MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, sse.data(), static_cast<int>(n), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, max_abs.data(), static_cast<int>(n), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, levels.data(), static_cast<int>(n), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  std::vector<uint64_t> first(n + 1, 0);
  for (uint64_t t = 0; t < n; ++t) first[t + 1] = first[t] + all_counts[t];
  std::vector<uint32_t> lengths(first[n], 0);
  for (uint64_t t = 0; t < n; ++t)
    for (size_t j = 0; j < mine[t].chunks.size(); ++j)
      lengths[first[t] + j] = static_cast<uint32_t>(mine[t].chunks[j].second.size());
  MPI_Allreduce(MPI_IN_PLACE, lengths.data(), static_cast<int>(lengths.size()), MPI_UINT32_T, MPI_SUM,
                MPI_COMM_WORLD);
  ErrorTally tally;
  MPI_Allreduce(&local.valid, &tally.valid, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(&local.lo, &tally.lo, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(&local.hi, &tally.hi, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  // In tile order, as one process adds them, so the recorded figures agree to the bit.
  for (uint64_t t = 0; t < n; ++t) {
    TileResult r;
    r.sse = sse[t];
    r.max_abs = max_abs[t];
    r.levels = static_cast<int>(levels[t]);
    tally.addTile(r);
  }
  std::vector<std::vector<uint32_t>> per_tile(n);
  for (uint64_t t = 0; t < n; ++t) per_tile[t].assign(lengths.begin() + first[t], lengths.begin() + first[t + 1]);
  std::vector<uint8_t> index, tile_counts;
  if (Error e = tileIndexPayload(per_tile, &index, &tile_counts); !e.ok())
    return agree(cli::kExitInvalidData, in + ": " + e.field + ": " + e.message);
  WaveletEncodeReport report;
  const std::vector<uint8_t> head = tiledStreamHead(h, tally.record(metadata, options, &report), tiling, index);
  ChunkView tidx{kChunkTileIndex, static_cast<uint32_t>(index.size()), 0,
                 head.size() - kChunkHeaderSize - index.size() - kChunkCrcSize, index.data()};
  TileIndex placed;
  if (Error e = parseTileIndex(tidx, n, &placed); !e.ok()) return agree(cli::kExitInvalidData, e.message);

  SharedFile file;
  if (int s = agree(file.open(out) ? 0 : cli::kExitIo, out + ": cannot create the output with MPI-IO")) return s;
  bool ok = true;
  if (rank == 0) {
    const std::vector<uint8_t> end = framedChunk(kChunkEnd, nullptr, 0);
    ok = file.writeAt(0, head.data(), head.size()) && file.writeAt(placed.end_offset, end.data(), end.size());
  }
  for (uint64_t t = 0; t < n && ok; ++t)
    for (size_t j = 0; j < mine[t].chunks.size() && ok; ++j) {
      const auto& [type, payload] = mine[t].chunks[j];
      const std::vector<uint8_t> framed = framedChunk(type, payload.data(), static_cast<uint32_t>(payload.size()));
      ok = file.writeAt(placed.chunk_offset[first[t] + j], framed.data(), framed.size());
    }
  status = agree(ok ? 0 : cli::kExitIo, out + ": an MPI-IO write failed");
  status = file.finish(status);
  if (status == 0 && rank == 0)
    std::fprintf(stderr, "mrsv-mpi encode: %s: %llu bytes, %.4f bits/sample, max error %g, %d ranks, %.3f s\n",
                 out.c_str(), static_cast<unsigned long long>(placed.end_offset + kChunkHeaderSize + kChunkCrcSize),
                 8.0 * static_cast<double>(placed.end_offset + 12) / static_cast<double>(h.sampleCount()),
                 report.max_abs_error, ranks, elapsed());
  return status;
}

int runDecode(int argc, char** argv) {
  Args args;
  std::string error;
  if (!args.parse(argc, argv, {{"threads"}, {"help"}, {}}, &error)) return agree(cli::kExitUsage, error);
  if (args.flag("help")) {
    if (rank == 0) std::fputs(kHelp, stdout);
    return 0;
  }
  if (args.positional().size() != 2) return agree(cli::kExitUsage, "decode needs IN.mrsv and OUT.raw");
  const std::string& in = args.positional()[0];
  const std::string& out = args.positional()[1];
  std::unique_ptr<ByteSource> source = openFileByteSource(in, &error);
  if (int s = agree(source ? 0 : cli::kExitIo, in + ": " + error)) return s;
  // The grid header first: a one-sample region of the first tile.
  DecodedGrid probe;
  GridRegion one;
  Error e = decodeGridRegion(*source, one, DecodeOptions{}, &probe);
  if (int s = agree(e.ok() ? 0 : cli::kExitInvalidData, in + ": " + e.describe())) return s;
  const GridHeader& h = probe.header;
  const bool precincts = h.coding == GridCoding::kWavelet && probe.wavelet.precinct_log2 > 0;
  if (int s = agree(h.coding == GridCoding::kTiled || precincts ? 0 : cli::kExitUsage,
                    in + ": neither a tiled grid (encode --tile) nor a grid in precincts (--precinct)"))
    return s;
  // The units a rank's band is made of: tiles, or precincts (2^P samples).
  uint32_t unit[3];
  for (int a = 0; a < 3; ++a) unit[a] = precincts ? 1u << probe.wavelet.precinct_log2 : probe.tile_size[a];
  // Bands of the slowest axis, a whole number of units each: contiguous in
  // OUT. (A band of another axis is not: with one unit along z, rank 0
  // decodes the whole grid.)
  const int axis = h.num_dims - 1;
  const uint32_t sizes[3] = {h.size_x, h.size_y, h.size_z};
  const uint32_t rows = (sizes[axis] + unit[axis] - 1) / unit[axis];
  const uint32_t per_rank = (rows + ranks - 1) / ranks;
  GridRegion band;
  for (int a = 0; a < 3; ++a) band.hi[a] = sizes[a];
  band.lo[axis] = std::min<uint64_t>(sizes[axis], static_cast<uint64_t>(rank) * per_rank * unit[axis]);
  band.hi[axis] = std::min<uint64_t>(sizes[axis], static_cast<uint64_t>(rank + 1) * per_rank * unit[axis]);
  DecodeOptions options;
  if (args.has("threads")) {
    uint64_t threads = 0;
    if (!cli::parseUint64(args.value("threads"), &threads) || threads < 1 || threads > 1024)
      return agree(cli::kExitUsage, "--threads must be 1 to 1024");
    options.threads = static_cast<int>(threads);
  }
  uint64_t stride = sampleSize(h.sample_type);
  for (int a = 0; a < axis; ++a) stride *= sizes[a];
  SharedFile file;
  if (int s = agree(file.open(out) ? 0 : cli::kExitIo, out + ": cannot create the output with MPI-IO")) return s;
  // The band a row of units at a time (or as many as make 8 MiB of samples),
  // each written as soon as decoded: memory stays bounded whatever the grid.
  // Measured on the 12,010² mosaic in precincts of 256 (a row is 6 MB): 134
  // MB per rank, 26.2 s on 1 rank, 14.2 s on 2; rows of 32 MiB: 582 MB, 24.2
  // and 13.3 s; the whole band at once: 5.1 GB, 28.0 and 14.3 s.
  const uint64_t row_bytes = stride * unit[axis];
  const uint32_t step = unit[axis] * static_cast<uint32_t>(std::max<uint64_t>(1, (uint64_t{8} << 20) / row_bytes));
  int status = 0;
  for (uint64_t lo = band.lo[axis]; lo < band.hi[axis] && status == 0; lo += step) {
    GridRegion rows = band;
    rows.lo[axis] = lo;
    rows.hi[axis] = std::min<uint64_t>(band.hi[axis], lo + step);
    DecodedGrid part;
    e = decodeGridRegion(*source, rows, options, &part);
    if (!e.ok()) {
      status = cli::kExitInvalidData;
      error = in + ": " + e.describe();
    } else if (!part.has_samples) {
      status = cli::kExitInvalidData;
      error = in + ": the stream ends before its samples";
    } else if (!file.writeAt(lo * stride, part.samples.data(), part.samples.size())) {
      status = cli::kExitIo;
      error = out + ": an MPI-IO write failed";
    }
  }
  status = file.finish(agree(status, error));
  if (status == 0 && rank == 0)
    std::fprintf(stderr, "mrsv-mpi decode: %s: %ux%ux%u, %d ranks, %.3f s\n", out.c_str(), sizes[0], sizes[1], sizes[2],
                 ranks, elapsed());
  return status;
}

}  // namespace
}  // namespace mrsv::mpi

int main(int argc, char** argv) {
  mrsv::cli::keepTileBuffersInTheHeap();
  // Serialized: the threads of a rank take turns at MPI-IO and the work
  // queue (each behind a mutex).
  int provided = MPI_THREAD_SINGLE;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  mrsv::mpi::serialized = provided >= MPI_THREAD_SERIALIZED;
  MPI_Comm_rank(MPI_COMM_WORLD, &mrsv::mpi::rank);
  MPI_Comm_size(MPI_COMM_WORLD, &mrsv::mpi::ranks);
  MPI_Barrier(MPI_COMM_WORLD);
  mrsv::mpi::started = MPI_Wtime();
  int status = 0;
  const std::string command = argc > 1 ? argv[1] : "";
  if (command == "encode") {
    status = mrsv::mpi::runEncode(argc - 2, argv + 2);
  } else if (command == "decode") {
    status = mrsv::mpi::runDecode(argc - 2, argv + 2);
  } else if (command == "--help" || command == "-h") {
    if (mrsv::mpi::rank == 0) std::fputs(mrsv::mpi::kHelp, stdout);
  } else {
    if (mrsv::mpi::rank == 0) std::fputs(mrsv::mpi::kHelp, stderr);
    status = mrsv::cli::kExitUsage;
  }
  MPI_Finalize();
  return status;
}
