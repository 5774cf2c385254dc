// mrsv decode: an MRSV file (or a prefix of one) to raw samples.
#include <algorithm>
#include <climits>
#include <condition_variable>
#include <cstdio>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

#include "cli.h"
#include "commands.h"
#include "bitstream/container_framer.h"
#include "common/parallel_for.h"
#include "mrsv/file_io.h"
#include "mrsv/grid_formats.h"
#include "mrsv/grid.h"
#include "mrsv/progressive_mesh.h"
#include "mrsv/progressive_tet_mesh.h"
#include "mrsv/raw_grid.h"
#include "mrsv/mesh_formats.h"
#include "mrsv/stream_decoder.h"
#include "mrsv/tet_formats.h"
#include "stream_input.h"

namespace mrsv::cli {
namespace {

// The rows of a tiled grid's whole decode (DecodeOptions::tile_rows) written
// to a raw or NRRD OUT (after `head`, the NRRD header) by a thread of their own, one row at a time, while the next
// row decodes: the write, one pass of the kernel over the whole output, no
// longer waits for the last tile, and the memory is two rows of tiles. The
// file appears under its name only when commit() succeeds.
class RowWriter {
 public:
  RowWriter(std::string path, std::vector<uint8_t> head, bool big_endian, size_t sample_bytes)
      : path_(std::move(path)), head_(std::move(head)), big_endian_(big_endian), sample_bytes_(sample_bytes) {}
  ~RowWriter() { stop(); }

  bool started() const { return started_; }

  // Hands over a row (taken from `samples`); false once a write has failed.
  bool push(std::vector<uint8_t>& samples) {
    if (!started_) {
      if (!file_.open(path_, &error_) || !file_.write(head_.data(), head_.size())) return false;
      started_ = true;
      thread_ = std::thread([this] { run(); });
    }
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [this] { return !full_ || failed_; });
    if (failed_) return false;
    pending_.swap(samples);
    full_ = true;
    ready_.notify_one();
    return true;
  }

  // Waits for the last row and renames the file into place.
  bool commit(std::string* error) {
    stop();
    if (failed_ || !file_.commit(&error_)) {
      *error = path_ + ": " + (error_.empty() ? "cannot write it" : error_);
      return false;
    }
    return true;
  }

 private:
  void run() {
    std::vector<uint8_t> row;
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(mutex_);
        ready_.wait(lock, [this] { return full_ || done_; });
        if (!full_) return;
        row.swap(pending_);
        full_ = false;
        idle_.notify_one();
      }
      if (big_endian_) swapSampleBytes(&row, sample_bytes_);
      if (!file_.write(row.data(), row.size())) {
        std::lock_guard<std::mutex> lock(mutex_);
        failed_ = true;
        idle_.notify_one();
        return;
      }
    }
  }
  void stop() {
    if (!thread_.joinable()) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
      ready_.notify_one();
    }
    thread_.join();
  }

  std::string path_, error_;
  std::vector<uint8_t> head_;
  bool big_endian_;
  size_t sample_bytes_;
  AtomicFileWriter file_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable ready_, idle_;
  std::vector<uint8_t> pending_;
  bool started_ = false, full_ = false, done_ = false, failed_ = false;
};

const char kHelp[] =
    "Usage: mrsv decode [options] IN.mrsv OUT\n"
    "\n"
    "IN '-' reads standard input (cat f.mrsv | mrsv decode - out.nrrd, curl URL | mrsv\n"
    "decode - out.nrrd). The input is decoded while it arrives: each chunk once, when\n"
    "it is complete (spec 2.7).\n"
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
    "  --threads N           tiles, or rows of precincts, decoded at once (default: the number\n"
    "                        of cores). A whole grid in precincts to raw or NRRD is decoded a\n"
    "                        row of precincts at a time, each by region: memory for a few rows\n"
    "  --bytes N             read only the first N bytes of IN, as if the rest had not\n"
    "                        arrived: the complete chunks among them are decoded\n"
    "  --levels-out PATTERN  also write each level as soon as its bytes have arrived:\n"
    "                        PATTERN with {level} replaced by the level number, or\n"
    "                        without {level}, '-L<level>' put before its extension.\n"
    "                        Grids: level K is the grid K levels above the finest\n"
    "                        (as --levels K), from the coarsest to the one OUT holds.\n"
    "                        PM and PT streams: level 0 is the base mesh, level K the\n"
    "                        mesh after K batches of splits; format as for OUT.\n"
    "                        Each file is written under a temporary name and renamed\n"
    "  --quiet               no progress or notes on stderr\n"
    "  --help                this text\n"
    "\n"
    "\n"
    "A file that ends after a complete chunk but before MEND is a prefix and decodes\n"
    "to what its complete chunks hold. OUT is written under a temporary name and renamed\n"
    "when complete. Exit status: 0 done, 1 invalid stream, 2 usage error, 3 file error.\n";

// PATTERN's file for `level` (see --levels-out).
std::string levelPath(const std::string& pattern, int level) {
  const std::string number = std::to_string(level);
  const size_t at = pattern.find("{level}");
  if (at != std::string::npos) return pattern.substr(0, at) + number + pattern.substr(at + 7);
  const size_t slash = pattern.find_last_of('/');
  size_t dot = pattern.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) dot = pattern.size();
  return pattern.substr(0, dot) + "-L" + number + pattern.substr(dot);
}

Error ioError(const std::string& message) { return Error{Status::kIoError, 0, "--levels-out", message}; }

// Whether the file keeps every framing rule of chapter 2 (each chunk whole,
// its CRC-32C right, the order rules, MEND last), a chunk in memory at a
// time: a decode by regions reads chunks in part (5.7.6 lets it skip their
// CRCs), so the whole decode by precinct rows checks them first.
bool chunksIntact(ByteSource& source) {
  ContainerFramer framer{ContainerOptions{}};
  Container container;
  const uint64_t size = source.size();
  uint8_t file_header[kFileHeaderSize];
  if (size < kFileHeaderSize || !source.read(0, kFileHeaderSize, file_header) ||
      !framer.fileHeader(file_header, kFileHeaderSize, &container).ok())
    return false;
  std::vector<uint8_t> chunk_bytes;
  for (uint64_t at = kFileHeaderSize; !container.complete;) {
    uint8_t head[kChunkHeaderSize];
    ChunkView chunk;
    if (at + kChunkHeaderSize > size || !source.read(at, sizeof head, head) ||
        !framer.chunkHeader(head, at, &chunk).ok() || chunk.endOffset() > size)
      return false;
    chunk_bytes.resize(chunk.endOffset() - at);
    if (!source.read(at, chunk_bytes.size(), chunk_bytes.data()) ||
        !framer.wholeChunk(chunk_bytes.data(), &chunk, &container).ok())
      return false;
    at = chunk.endOffset();
    if (container.complete) return at == size;
  }
  return false;
}

// A grid in precincts (5.7.6) decoded whole to raw or NRRD as rows of
// precincts along the slowest axis (each as many rows as make 8 MiB of
// samples), each by region on a thread of its own, `threads` rows at once,
// written in order as they come: the memory is a few rows, not the grid
// (the whole decoder holds every coefficient: 2.6 GB for the 12,010² mosaic,
// 134 MB this way), and the threads share the work (the whole decoder has
// one). False when IN is not such a stream or anything in it breaks a rule:
// the caller then decodes it the usual way, which reports the first rule
// broken. `*status` is the exit status otherwise.
bool decodeByPrecinctRows(const std::string& in, const std::string& out, int threads, Endian endian, Progress* progress,
                          int* status) {
  std::string error;
  std::unique_ptr<ByteSource> source = openFileByteSource(in, &error);
  if (!source) return false;
  DecodedGrid probe;
  if (!decodeGridRegion(*source, GridRegion{}, DecodeOptions{}, &probe).ok() || !probe.region_by_precincts ||
      !chunksIntact(*source))
    return false;
  const GridHeader& h = probe.header;
  const int axis = h.num_dims - 1;
  const uint32_t sizes[3] = {h.size_x, h.size_y, h.size_z};
  uint64_t row_bytes = sampleSize(h.sample_type) << probe.wavelet.precinct_log2;
  for (int a = 0; a < axis; ++a) row_bytes *= sizes[a];
  const uint64_t step = std::max<uint64_t>(1, (uint64_t{8} << 20) / row_bytes) << probe.wavelet.precinct_log2;
  const uint64_t rows = (sizes[axis] + step - 1) / step;
  std::vector<uint8_t> head;
  if (!encodeGridOutput(out, h, Metadata{}, sizes, {}, endian == Endian::kBig, &head, &error)) return false;
  RowWriter writer(out, std::move(head), endian == Endian::kBig, sampleSize(h.sample_type));
  for (uint64_t first = 0; first < rows; first += static_cast<uint64_t>(threads)) {
    std::vector<DecodedGrid> parts(std::min<uint64_t>(static_cast<uint64_t>(threads), rows - first));
    std::vector<char> ok(parts.size(), 0);
    parallelFor(parts.size(), threads, [&](uint64_t i) {
      std::string why;
      std::unique_ptr<ByteSource> own = openFileByteSource(in, &why);  // a source per thread
      GridRegion box;
      for (int a = 0; a < 3; ++a) box.hi[a] = sizes[a];
      box.lo[axis] = static_cast<uint32_t>((first + i) * step);
      box.hi[axis] = static_cast<uint32_t>(std::min<uint64_t>(sizes[axis], (first + i + 1) * step));
      ok[i] = own && decodeGridRegion(*own, box, DecodeOptions{}, &parts[i]).ok() && parts[i].region_by_precincts &&
              parts[i].has_samples;
    });
    for (size_t i = 0; i < parts.size(); ++i) {
      if (!ok[i]) return false;  // the writer's file is not committed: nothing is left
      if (!writer.push(parts[i].samples)) {
        std::string why;
        writer.commit(&why);
        *status = fail("decode", why.empty() ? out + ": cannot write it" : why, kExitIo);
        return true;
      }
    }
    progress->update(0.1 + 0.9 * static_cast<double>(first + parts.size()) / static_cast<double>(rows));
  }
  *status = writer.commit(&error) ? kExitOk : fail("decode", error, kExitIo);
  return true;
}

// Feeds `head` and then the rest of `input` to `decoder`, calling
// `on_units` after each piece, then finishes it.
Error decodeInput(StreamInput* input, const std::vector<uint8_t>& head, StreamDecoder* decoder,
                  const std::function<Error()>& on_units) {
  if (Error e = decoder->feed(head.data(), head.size()); !e.ok()) return e;
  if (Error e = on_units(); !e.ok()) return e;
  std::vector<uint8_t> piece;
  std::string error;
  for (;;) {
    if (!input->next(&piece, &error)) return Error{Status::kIoError, decoder->bytesFed(), "input", error};
    if (piece.empty()) break;
    if (Error e = decoder->feed(piece.data(), piece.size()); !e.ok()) return e;
    if (Error e = on_units(); !e.ok()) return e;
  }
  Error e = input->cutShort() ? decoder->finishPrefix() : decoder->finish();
  if (e.ok()) e = on_units();
  return e;
}

}  // namespace

int runDecode(int argc, char** argv) {
  const char* cmd = "decode";
  Args args;
  std::string error;
  if (!args.parse(argc, argv, {{"endian", "bytes", "levels", "levels-out", "faces", "tets", "vertices", "fraction", "region", "threads"}, {"canonical", "quiet", "help"}, {}}, &error))
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
  const std::string levels_out = args.has("levels-out") ? args.value("levels-out") : "";
  if (args.has("levels-out") && levels_out.empty()) return fail(cmd, "--levels-out needs a PATTERN", kExitUsage);
  if (in != "-" && isSameFile(in, out)) return fail(cmd, "OUT is the same file as IN; refusing to overwrite the input", kExitUsage);
  const bool quiet = args.flag("quiet");
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
  if (by_region && !args.has("bytes") && in != "-")
    return runRegionDecode(args, in, out, region, threads, endian, levels);

  Progress progress("decode", quiet);
  const GridFormat out_format = gridFormatOf(out);
  if (!by_region && in != "-" && !args.has("bytes") && levels == 0 && levels_out.empty() &&
      !args.flag("canonical") && (out_format == GridFormat::kRaw || out_format == GridFormat::kNrrd)) {
    int status = kExitOk;
    if (decodeByPrecinctRows(in, out, threads, endian, &progress, &status)) return status;
  }
  StreamInput input;
  if (!input.open(in, byte_limit, &error)) return fail(cmd, error, kExitIo);
  if (by_region) {  // a prefix (--bytes) or standard input: a region of the bytes in memory
    std::vector<uint8_t> bytes, piece;
    for (;;) {
      if (!input.next(&piece, &error)) return fail(cmd, error, kExitIo);
      if (piece.empty()) break;
      bytes.insert(bytes.end(), piece.begin(), piece.end());
    }
    MemoryByteSource source(bytes.data(), bytes.size());
    return runRegionDecode(args, input.name(), out, region, threads, endian, levels, &source);
  }
  // The content header's type (bytes 12 to 15) says which decoder to run.
  std::vector<uint8_t> head, piece;
  while (head.size() < kFileHeaderSize + 4) {
    if (!input.next(&piece, &error)) return fail(cmd, error, kExitIo);
    if (piece.empty()) break;
    head.insert(head.end(), piece.begin(), piece.end());
  }
  DecodeOptions options;
  options.reduce_levels = static_cast<int>(levels);
  options.threads = threads;

  if (isProgressiveMeshStream(head.data(), head.size())) {
    const MeshDecodeFn decode = [&](const DecodeOptions& o, DecodedMesh* decoded) {
      StreamDecoder decoder(o, StreamContent::kMesh);
      Error e = decodeInput(&input, head, &decoder, [&]() -> Error {
        for (const StreamUnit& unit : decoder.takeUnits()) {
          if (levels_out.empty() || (unit.chunk_type != kChunkBaseMesh && unit.chunk_type != kChunkSplits)) continue;
          const int level = unit.chunk_type == kChunkBaseMesh ? 0 : static_cast<int>(unit.index) + 1;
          const std::string path = levelPath(levels_out, level);
          std::vector<uint8_t> bytes;
          std::string why;
          if (!encodeMeshFile(path, decoder.mesh().mesh.mesh(), &bytes, &why)) return ioError(why);
          if (!writeFileAtomically(path, bytes, &why)) return ioError(path + ": " + why);
          if (!quiet) std::fprintf(stderr, "mrsv decode: %s: level %d\n", path.c_str(), level);
        }
        return {};
      });
      *decoded = std::move(decoder.mesh());
      return e;
    };
    return runMeshDecode(args, input.name(), out, decode, options);
  }
  if (isProgressiveTetStream(head.data(), head.size())) {
    const TetDecodeFn decode = [&](const DecodeOptions& o, DecodedTetMesh* decoded) {
      StreamDecoder decoder(o, StreamContent::kTetMesh);
      Error e = decodeInput(&input, head, &decoder, [&]() -> Error {
        for (const StreamUnit& unit : decoder.takeUnits()) {
          if (levels_out.empty() || (unit.chunk_type != kChunkTetBase && unit.chunk_type != kChunkTetSplits)) continue;
          const int level = unit.chunk_type == kChunkTetBase ? 0 : static_cast<int>(unit.index) + 1;
          const std::string path = levelPath(levels_out, level);
          TetWriteReport report;
          std::string why;
          if (!writeTetFile(path, decoder.tetMesh().mesh.mesh(), TetWriteOptions{}, &report, &why))
            return ioError(path + ": " + why);
          if (!quiet) std::fprintf(stderr, "mrsv decode: %s: level %d\n", path.c_str(), level);
        }
        return {};
      });
      *decoded = std::move(decoder.tetMesh());
      return e;
    };
    return runTetDecode(args, input.name(), out, decode, options);
  }
  if (args.has("faces") || args.has("tets") || args.has("vertices") || args.has("fraction"))
    return fail(cmd, input.name() + ": --faces, --tets, --vertices and --fraction are for mesh streams; this is a grid",
                kExitUsage);
  if (levels > 0 && args.flag("canonical"))
    return fail(cmd, "--canonical is defined at full resolution only", kExitUsage);
  progress.update(0.2);

  // A grid: each band decoded as it arrives; with --levels-out each level's
  // samples synthesised from the level above when its last band is in.
  DecodeOptions grid_options = options;
  if (!levels_out.empty()) grid_options.whole_array_synthesis = true;  // the same samples (grid.h)
  StreamDecoder decoder(grid_options, StreamContent::kGrid);
  // A tiled grid decoded whole to raw or NRRD: written a row of tiles at a time.
  std::unique_ptr<RowWriter> rows;
  if ((out_format == GridFormat::kRaw || out_format == GridFormat::kNrrd) && !args.flag("canonical") &&
      levels_out.empty()) {
    DecodeOptions row_options = grid_options;
    row_options.tile_rows = [&](int, uint32_t, uint32_t, std::vector<uint8_t>& samples) {
      if (!rows) {
        // The output's header (NRRD; none for raw) from the whole output's sizes (spec 11.6).
        const GridHeader& h = decoder.grid().header;
        const uint32_t step = 1u << levels;
        const uint32_t size[3] = {(h.size_x + step - 1) / step, (h.size_y + step - 1) / step,
                                  (h.size_z + step - 1) / step};
        std::vector<uint8_t> head;
        std::string why;
        if (!encodeGridOutput(out, h, Metadata{}, size, {}, endian == Endian::kBig, &head, &why)) return false;
        rows = std::make_unique<RowWriter>(out, std::move(head), endian == Endian::kBig, sampleSize(h.sample_type));
      }
      return rows->push(samples);
    };
    decoder = StreamDecoder(row_options, StreamContent::kGrid);
  }
  int next_level = INT_MAX;  // the levels from here up are written
  auto writeLevel = [&](int level, const uint32_t size[3], std::vector<uint8_t> samples) -> Error {
    const DecodedGrid& g = decoder.grid();
    const std::string path = levelPath(levels_out, level);
    const Metadata metadata = reducedResolutionMetadata(g.metadata, g.header, g.wavelet.levels, level);
    std::vector<uint8_t> bytes;
    std::string why;
    if (!encodeGridOutput(path, g.header, metadata, size, std::move(samples), endian == Endian::kBig, &bytes, &why))
      return ioError(why);
    if (!writeFileAtomically(path, bytes, &why)) return ioError(path + ": " + why);
    if (!quiet) std::fprintf(stderr, "mrsv decode: %s: level %d, %ux%ux%u\n", path.c_str(), level, size[0], size[1], size[2]);
    return {};
  };
  Error e = decodeInput(&input, head, &decoder, [&]() -> Error {
    for (const StreamUnit& unit : decoder.takeUnits()) {
      if (levels_out.empty() || unit.complete_level < 0) continue;
      const DecodedGrid& g = decoder.grid();
      const int coarsest = std::max({int{g.wavelet.levels[0]}, int{g.wavelet.levels[1]}, int{g.wavelet.levels[2]}});
      const int finest = std::max({unit.complete_level, static_cast<int>(levels), 1});
      for (int r = std::min(next_level - 1, coarsest); r >= finest; --r) {
        uint32_t size[3];
        std::vector<uint8_t> samples;
        if (Error le = decoder.gridLevelSamples(r, size, &samples); !le.ok()) return le;
        next_level = r;
        if (Error we = writeLevel(r, size, std::move(samples)); !we.ok()) return we;
      }
    }
    return {};
  });
  if (!e.ok()) return reportError(cmd, input.name(), e);
  DecodedGrid& grid = decoder.grid();
  progress.update(0.8);
  if (!levels_out.empty() && grid.has_samples && static_cast<int>(levels) < next_level)
    if (Error we = writeLevel(static_cast<int>(levels), grid.output_size, grid.samples); !we.ok())
      return reportError(cmd, input.name(), we);

  if (rows && rows->started()) {
    if (!grid.has_samples)
      return fail(cmd, input.name() + ": the stream ends before its sample data", kExitInvalidData);
    if (!rows->commit(&error)) return fail(cmd, error, kExitIo);
    if (!quiet && (grid.output_size[0] != grid.header.size_x || grid.output_size[1] != grid.header.size_y ||
                   grid.output_size[2] != grid.header.size_z))
      std::fprintf(stderr, "mrsv decode: %s: reduced resolution %ux%ux%u\n", out.c_str(), grid.output_size[0],
                   grid.output_size[1], grid.output_size[2]);
    progress.update(1.0);
    return kExitOk;
  }
  std::vector<uint8_t> output;
  if (args.flag("canonical")) {
    output = canonicalGridOutput(grid);
  } else {
    if (!grid.has_samples)
      return fail(cmd, input.name() + ": the stream ends before its sample data (a prefix of " +
                           std::to_string(grid.container.chunks.size()) + " chunks)",
                  kExitInvalidData);
    const Metadata metadata = decodedGridMetadata(grid, options.reduce_levels);
    if (!encodeGridOutput(out, grid.header, metadata, grid.output_size, std::move(grid.samples),
                          endian == Endian::kBig, &output, &error))
      return fail(cmd, error, kExitUsage);
  }
  if (!quiet && !args.flag("canonical") &&
      (grid.output_size[0] != grid.header.size_x || grid.output_size[1] != grid.header.size_y ||
       grid.output_size[2] != grid.header.size_z))
    std::fprintf(stderr, "mrsv decode: %s: reduced resolution %ux%ux%u\n", out.c_str(),
                 grid.output_size[0], grid.output_size[1], grid.output_size[2]);
  if (!grid.container.complete && !quiet)
    std::fprintf(stderr, "mrsv decode: %s: note: stream is a prefix (no MEND); decoded its %zu complete chunks\n",
                 input.name().c_str(), grid.container.chunks.size());
  if (!writeFileAtomically(out, output, &error)) return fail(cmd, out + ": " + error, kExitIo);
  progress.update(1.0);
  return kExitOk;
}

}  // namespace mrsv::cli
