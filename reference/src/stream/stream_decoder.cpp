// spec: 2.7 (informative) incremental decoding. The framing steps of
// bitstream/container_framer.h and each profile's chunk steps
// (grid/grid_steps.h, pm/pm_steps.h, pt/pt_steps.h) run as the bytes arrive.
#include "mrsv/stream_decoder.h"

#include <algorithm>
#include <utility>

#include "bitstream/container_framer.h"
#include "grid/grid_steps.h"
#include "pm/pm_steps.h"
#include "pt/pt_steps.h"
#include "stream/stream_internal.h"

namespace mrsv {

struct StreamDecoder::Impl {
  explicit Impl(const DecodeOptions& o, StreamContent e) : options(o), expect(e), framer(o.container) {}

  DecodeOptions options;
  StreamContent expect;
  StreamContent content = StreamContent::kUnknown;
  ContainerFramer framer;
  WaveletCoefficients* keep = nullptr;  // decodeGridKeepingCoefficients()

  // The results; `container` is that of the one content() names (the grid's
  // until the content header is read).
  DecodedGrid grid;
  DecodedMesh mesh;
  DecodedTetMesh tets;
  Container* container = &grid.container;
  std::unique_ptr<GridSteps> grid_steps;
  std::unique_ptr<PmSteps> pm_steps;
  std::unique_ptr<PtSteps> pt_steps;

  // The unit being gathered: the file header (12 bytes), a chunk's header
  // (8), then the whole chunk. `pending` holds its bytes when they came in
  // more than one piece.
  enum class Stage { kFileHeader, kChunks, kEnded } stage = Stage::kFileHeader;
  uint64_t pos = 0;  // stream offset of the unit
  size_t need = kFileHeaderSize;
  bool chunk_header_read = false;
  ChunkView current;
  std::vector<uint8_t> pending;

  uint64_t fed = 0;
  uint64_t trailing = 0;  // bytes after MEND
  Error error;
  bool finished = false;
  std::vector<StreamUnit> units;

  Error fail(Error e) {
    error = std::move(e);
    return error;
  }
  Error step(const uint8_t* unit, bool* consumed);
  Error contentHeader(const ChunkView& chunk);
  Error chunk(const ChunkView& chunk);
  Error feed(const uint8_t* data, size_t size);
  Error finish();
};

Error StreamDecoder::Impl::contentHeader(const ChunkView& chunk) {
  // The framing guarantees the first chunk is GHDR, PHDR or THDR (spec 2.5).
  content = chunk.chunk_type == kChunkGridHeader   ? StreamContent::kGrid
            : chunk.chunk_type == kChunkMeshHeader ? StreamContent::kMesh
                                                   : StreamContent::kTetMesh;
  if (expect != StreamContent::kUnknown && content != expect) {
    // Each one-shot decoder reads its profile only (spec 1.6).
    const char* what = expect == StreamContent::kGrid
                           ? "not a grid stream (the content header is not GHDR; spec 1.6)"
                       : expect == StreamContent::kMesh
                           ? "not a progressive mesh stream (the content header is not PHDR; spec 1.6)"
                           : "not a progressive tet mesh stream (the content header is not THDR; spec 1.6)";
    content = expect;
    return Error{Status::kUnsupportedProfile, chunk.offset, chunk.chunk_type.str(), what};
  }
  switch (content) {
    case StreamContent::kGrid:
      grid_steps = std::make_unique<GridSteps>(options, &grid, keep);
      return grid_steps->header(chunk);
    case StreamContent::kMesh:
      mesh.container = std::move(grid.container);
      grid.container = Container{};
      container = &mesh.container;
      pm_steps = std::make_unique<PmSteps>(options, &mesh);
      return pm_steps->header(chunk);
    default:
      tets.container = std::move(grid.container);
      grid.container = Container{};
      container = &tets.container;
      pt_steps = std::make_unique<PtSteps>(options, &tets);
      return pt_steps->header(chunk);
  }
}

Error StreamDecoder::Impl::chunk(const ChunkView& chunk) {
  StreamUnit unit;
  unit.chunk_type = chunk.chunk_type;
  unit.offset = chunk.offset;
  unit.end_offset = chunk.endOffset();
  if (container->chunks.size() == 1) {
    if (Error e = contentHeader(chunk); !e.ok()) return e;
  } else if (grid_steps) {
    if (chunk.chunk_type == kChunkBand) unit.index = grid.bands_decoded;
    if (Error e = grid_steps->chunk(chunk); !e.ok()) return e;
  } else if (pm_steps) {
    unit.index = mesh.batches_decoded;
    if (Error e = pm_steps->chunk(chunk); !e.ok()) return e;
  } else if (pt_steps) {
    unit.index = tets.batches_decoded;
    if (Error e = pt_steps->chunk(chunk); !e.ok()) return e;
  }
  if (grid_steps && grid_steps->wavelet()) unit.complete_level = grid_steps->wavelet()->completeLevel();
  units.push_back(unit);
  return {};
}

// One unit whose `need` bytes are at `unit`. *consumed: the unit is done
// (false after a chunk header, whose bytes stay part of the chunk).
Error StreamDecoder::Impl::step(const uint8_t* unit, bool* consumed) {
  *consumed = false;
  if (stage == Stage::kFileHeader) {
    if (Error e = framer.fileHeader(unit, kFileHeaderSize, container); !e.ok()) return e;
    stage = Stage::kChunks;
    pos = kFileHeaderSize;
    need = kChunkHeaderSize;
    *consumed = true;
    return {};
  }
  if (!chunk_header_read) {
    if (Error e = framer.chunkHeader(unit, pos, &current); !e.ok()) return e;
    chunk_header_read = true;
    need = kChunkHeaderSize + size_t{current.chunk_length} + kChunkCrcSize;
    return {};
  }
  if (Error e = framer.wholeChunk(unit, &current, container); !e.ok()) return e;
  *consumed = true;
  pos = current.endOffset();
  need = kChunkHeaderSize;
  chunk_header_read = false;
  if (container->complete) {
    stage = Stage::kEnded;
    return {};
  }
  Error e = chunk(current);
  container->chunks.back().payload = nullptr;  // the bytes are not kept
  return e;
}

Error StreamDecoder::Impl::feed(const uint8_t* data, size_t size) {
  if (!error.ok()) return error;
  if (finished)
    return fail(Error{Status::kInvalidArgument, fed, "stream", "bytes fed after finish()"});
  fed += size;
  while (size > 0) {
    if (stage == Stage::kEnded) {
      trailing += size;  // an error, reported by finish() with their count
      return {};
    }
    bool consumed = false;
    if (pending.empty() && size >= need) {
      // The whole unit is in this piece: decoded in place, not copied.
      const size_t n = need;
      if (Error e = step(data, &consumed); !e.ok()) return fail(e);
      if (consumed) {
        data += n;
        size -= n;
      }
      continue;
    }
    const size_t take = std::min(need - pending.size(), size);
    pending.insert(pending.end(), data, data + take);
    data += take;
    size -= take;
    if (pending.size() < need) return {};
    if (Error e = step(pending.data(), &consumed); !e.ok()) return fail(e);
    if (consumed) pending.clear();
  }
  return {};
}

Error StreamDecoder::Impl::finish() {
  if (!error.ok()) return error;
  if (finished) return fail(Error{Status::kInvalidArgument, fed, "stream", "finish() called twice"});
  finished = true;
  if (stage == Stage::kFileHeader) {
    // Fewer than 12 bytes: the file header's rules on what there is.
    if (Error e = framer.fileHeader(pending.data(), pending.size(), container); !e.ok()) return fail(e);
  } else if (stage == Stage::kEnded) {
    if (trailing > 0) return fail(ContainerFramer::trailingBytes(*container, trailing));
  } else if (!pending.empty()) {
    if (Error e = framer.endsInsideChunk(pos, pending.size(), current, container); !e.ok())
      return fail(e);
  }
  pending.clear();
  pending.shrink_to_fit();
  Error e;
  if (grid_steps) e = grid_steps->end(*container);
  else if (pm_steps) e = pm_steps->end(*container);
  else if (pt_steps) e = pt_steps->end(*container);
  return e.ok() ? e : fail(e);
}

StreamDecoder::StreamDecoder(const DecodeOptions& options, StreamContent expect)
    : impl_(new Impl(options, expect)) {}
StreamDecoder::~StreamDecoder() = default;
StreamDecoder::StreamDecoder(StreamDecoder&&) noexcept = default;
StreamDecoder& StreamDecoder::operator=(StreamDecoder&&) noexcept = default;

Error StreamDecoder::feed(const uint8_t* data, size_t size) { return impl_->feed(data, size); }
Error StreamDecoder::finish() { return impl_->finish(); }
Error StreamDecoder::finishPrefix() {
  impl_->framer.allowPartialTail();
  return impl_->finish();
}
const Error& StreamDecoder::error() const { return impl_->error; }
bool StreamDecoder::finished() const { return impl_->finished; }
uint64_t StreamDecoder::bytesFed() const { return impl_->fed; }
StreamContent StreamDecoder::content() const { return impl_->content; }
std::vector<StreamUnit> StreamDecoder::takeUnits() {
  std::vector<StreamUnit> out;
  out.swap(impl_->units);
  return out;
}
DecodedGrid& StreamDecoder::grid() { return impl_->grid; }
DecodedMesh& StreamDecoder::mesh() { return impl_->mesh; }
DecodedTetMesh& StreamDecoder::tetMesh() { return impl_->tets; }

int StreamDecoder::gridCompleteLevel() const {
  const Impl& d = *impl_;
  return d.grid_steps && d.grid_steps->wavelet() ? d.grid_steps->wavelet()->completeLevel() : -1;
}

Error StreamDecoder::gridLevelSamples(int level, uint32_t size[3], std::vector<uint8_t>* samples) {
  Impl& d = *impl_;
  if (!d.error.ok()) return d.error;
  if (!d.grid_steps || !d.grid_steps->wavelet() || d.container->chunks.empty())
    return Error{Status::kInvalidArgument, d.pos, "levelSamples", "not a wavelet-coded grid"};
  return d.grid_steps->wavelet()->levelSamples(level, d.container->chunks.back(), size, samples);
}

namespace {

// The one-shot decoders: the stream fed all at once. Their chunk views point
// into `data`, which the caller keeps.
template <class Result>
Error oneShot(StreamDecoder* d, const uint8_t* data, size_t size, Result* result, Result* out) {
  Error e = d->feed(data, size);
  if (e.ok()) e = d->finish();
  *out = std::move(*result);
  for (ChunkView& chunk : out->container.chunks) chunk.payload = data + chunk.payloadOffset();
  return e;
}

}  // namespace

Error decodeGridOneShot(const uint8_t* data, size_t size, const DecodeOptions& options,
                        DecodedGrid* out, WaveletCoefficients* keep) {
  StreamDecoder d(options, StreamContent::kGrid);
  d.impl_->keep = keep;
  return oneShot(&d, data, size, &d.grid(), out);
}

Error decodeGrid(const uint8_t* data, size_t size, const DecodeOptions& options, DecodedGrid* out) {
  return decodeGridOneShot(data, size, options, out, nullptr);
}

Error decodeGridKeepingCoefficients(const uint8_t* data, size_t size, const DecodeOptions& options,
                                    DecodedGrid* out, WaveletCoefficients* coefficients) {
  return decodeGridOneShot(data, size, options, out, coefficients);
}

Error decodeProgressiveMesh(const uint8_t* data, size_t size, const DecodeOptions& options,
                            DecodedMesh* out) {
  StreamDecoder d(options, StreamContent::kMesh);
  return oneShot(&d, data, size, &d.mesh(), out);
}

Error decodeProgressiveTetMesh(const uint8_t* data, size_t size, const DecodeOptions& options,
                               DecodedTetMesh* out) {
  StreamDecoder d(options, StreamContent::kTetMesh);
  return oneShot(&d, data, size, &d.tetMesh(), out);
}

}  // namespace mrsv
