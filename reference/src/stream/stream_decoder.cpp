// spec: 2.7 (informative) incremental decoding. The framing steps of
// bitstream/container_framer.h and each profile's chunk steps
// (grid/grid_steps.h, pm/pm_steps.h, pt/pt_steps.h) run as the bytes arrive.
#include "mrsv/stream_decoder.h"

#include <algorithm>
#include <cstring>
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
  bool one_shot = false;  // all the bytes in one feed() the caller keeps until finish()

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
  // (8), then the whole chunk. pending[0, have) holds its bytes when they came in
  // more than one piece.
  enum class Stage { kFileHeader, kChunks, kEnded } stage = Stage::kFileHeader;
  uint64_t pos = 0;  // stream offset of the unit
  size_t need = kFileHeaderSize;
  bool chunk_header_read = false;
  ChunkView current;
  std::vector<uint8_t> pending;  // grows to the unit's size as its bytes arrive
  size_t have = 0;

  void append(const uint8_t* data, size_t n) {
    if (have + n > pending.size())  // doubling, not the chunk's length at once
      pending.resize(std::min(need, std::max({have + n, 2 * pending.size(), size_t{4096}})));
    uint8_t* to = pending.data() + have;
    if (n <= 8) {  // a byte or a few at a time: no call to memcpy
      for (size_t i = 0; i < n; ++i) to[i] = data[i];
    } else {
      std::memcpy(to, data, n);
    }
    have += n;
  }

  uint64_t fed = 0;
  uint64_t trailing = 0;  // bytes after MEND
  // The first rule broken by a chunk's content, and the rank Annex A.2 gives
  // it (3: content header, 4: meta, 5: memory, 6: other chunks). The framing
  // of the rest of the stream comes first in A.2, and the meta chunk before
  // ranks 5 and 6, so it is reported by finish() (unless one of those
  // breaks a rule), while nothing else is decoded after it.
  Error problem;
  int problem_rank = 0;
  Error error;  // final: a framing error, or what finish() reported
  bool finished = false;
  std::vector<StreamUnit> units;

  Error fail(Error e) {
    error = std::move(e);
    have = 0;  // (so that feed()'s shortcut takes no more bytes)
    return error;
  }
  void defer(Error e, int rank) {
    if (problem_rank == 0 || rank < problem_rank) {
      problem = std::move(e);
      problem_rank = rank;
    }
  }
  Error step(const uint8_t* unit, bool* consumed);
  void contentHeader(const ChunkView& chunk);
  void chunk(const ChunkView& chunk);
  Error feed(const uint8_t* data, size_t size, bool last = false);
  Error finish();
};

void StreamDecoder::Impl::contentHeader(const ChunkView& chunk) {
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
    return defer(Error{Status::kUnsupportedProfile, chunk.offset, chunk.chunk_type.str(), what}, 3);
  }
  Error e;
  switch (content) {
    case StreamContent::kGrid:
      grid_steps = std::make_unique<GridSteps>(options, &grid, keep);
      if (one_shot) grid_steps->bytesOutliveSteps();
      if (e = grid_steps->header(chunk); !e.ok()) return defer(e, 3);
      return;
    case StreamContent::kMesh:
      mesh.container = std::move(grid.container);
      grid.container = Container{};
      container = &mesh.container;
      pm_steps = std::make_unique<PmSteps>(options, &mesh);
      if (e = pm_steps->header(chunk); !e.ok()) return defer(e, 3);
      if (e = pm_steps->memory(chunk); !e.ok()) return defer(e, 5);
      return;
    default:
      tets.container = std::move(grid.container);
      grid.container = Container{};
      container = &tets.container;
      pt_steps = std::make_unique<PtSteps>(options, &tets);
      if (e = pt_steps->header(chunk); !e.ok()) return defer(e, 3);
      if (e = pt_steps->memory(chunk); !e.ok()) return defer(e, 5);
      return;
  }
}

void StreamDecoder::Impl::chunk(const ChunkView& chunk) {
  if (container->chunks.size() == 1) return contentHeader(chunk);
  // After a problem, only the meta chunk can still change what is reported.
  const bool meta = chunk.chunk_type == kChunkMeta;
  if (problem_rank != 0 && !(meta && problem_rank > 4)) return;
  StreamUnit unit;
  unit.chunk_type = chunk.chunk_type;
  unit.offset = chunk.offset;
  unit.end_offset = chunk.endOffset();
  Error e;
  if (grid_steps) {
    if (chunk.chunk_type == kChunkBand) unit.index = grid.bands_decoded;
    e = grid_steps->chunk(chunk);
  } else if (pm_steps) {
    unit.index = mesh.batches_decoded;
    e = pm_steps->chunk(chunk);
  } else if (pt_steps) {
    unit.index = tets.batches_decoded;
    e = pt_steps->chunk(chunk);
  }
  if (!e.ok()) return defer(e, meta ? 4 : 6);
  if (problem_rank != 0) return;
  if (grid_steps && grid_steps->wavelet()) unit.complete_level = grid_steps->wavelet()->completeLevel();
  units.push_back(unit);
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
  chunk(current);
  container->chunks.back().payload = nullptr;  // the bytes are not kept
  return {};
}

// `last`: finish() follows at once (the one-shot decoders), so the bytes of an
// incomplete last chunk need not be kept, only counted.
Error StreamDecoder::Impl::feed(const uint8_t* data, size_t size, bool last) {
  // Most calls of a stream fed in small pieces only add to the unit being
  // gathered (have > 0: not after MEND, not after an error or finish()).
  if (have != 0 && size < need - have && !finished) {
    append(data, size);
    fed += size;
    return {};
  }
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
    if (have == 0 && size >= need) {
      // The whole unit is in this piece: decoded in place, not copied.
      const size_t n = need;
      if (Error e = step(data, &consumed); !e.ok()) return fail(e);
      if (consumed) {
        data += n;
        size -= n;
      }
      continue;
    }
    const size_t take = std::min(need - have, size);
    if (last && take == size && stage == Stage::kChunks && chunk_header_read) {
      have += take;  // the stream ends inside this chunk: finish() needs the count only
      return {};
    }
    append(data, take);
    data += take;
    size -= take;
    if (have < need) return {};
    if (Error e = step(pending.data(), &consumed); !e.ok()) return fail(e);
    if (consumed) have = 0;
  }
  return {};
}

Error StreamDecoder::Impl::finish() {
  if (!error.ok()) return error;
  if (finished) return fail(Error{Status::kInvalidArgument, fed, "stream", "finish() called twice"});
  finished = true;
  if (stage == Stage::kFileHeader) {
    // Fewer than 12 bytes: the file header's rules on what there is.
    if (Error e = framer.fileHeader(pending.data(), have, container); !e.ok()) return fail(e);
  } else if (stage == Stage::kEnded) {
    if (trailing > 0) return fail(ContainerFramer::trailingBytes(*container, trailing));
  } else if (have > 0) {
    if (Error e = framer.endsInsideChunk(pos, have, current, container); !e.ok())
      return fail(e);
  }
  have = 0;
  std::vector<uint8_t>().swap(pending);
  if (problem_rank != 0) return fail(problem);
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
const Error& StreamDecoder::problem() const { return impl_->problem; }
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
  // (A level complete before a problem is still whole: the chunk breaking
  // the rule belongs to a finer level.)
  if (!d.error.ok()) return d.error;
  if (!d.grid_steps || !d.grid_steps->wavelet() || d.container->chunks.empty())
    return Error{Status::kInvalidArgument, d.pos, "levelSamples", "not a wavelet-coded grid"};
  return d.grid_steps->wavelet()->levelSamples(level, d.container->chunks.back(), size, samples);
}

struct OneShotAccess {
  static StreamDecoder::Impl* impl(StreamDecoder& d) { return d.impl_.get(); }
};

namespace {

// The one-shot decoders: the stream fed all at once. Their chunk views point
// into `data`, which the caller keeps.
template <class Result>
Error oneShot(StreamDecoder::Impl* d, const uint8_t* data, size_t size, Result* result, Result* out) {
  d->one_shot = true;
  Error e = d->feed(data, size, /*last=*/true);
  if (e.ok()) e = d->finish();
  *out = std::move(*result);
  for (ChunkView& chunk : out->container.chunks) chunk.payload = data + chunk.payloadOffset();
  return e;
}

}  // namespace

Error decodeGridOneShot(const uint8_t* data, size_t size, const DecodeOptions& options,
                        DecodedGrid* out, WaveletCoefficients* keep) {
  StreamDecoder d(options, StreamContent::kGrid);
  OneShotAccess::impl(d)->keep = keep;
  return oneShot(OneShotAccess::impl(d), data, size, &d.grid(), out);
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
  return oneShot(OneShotAccess::impl(d), data, size, &d.mesh(), out);
}

Error decodeProgressiveTetMesh(const uint8_t* data, size_t size, const DecodeOptions& options,
                               DecodedTetMesh* out) {
  StreamDecoder d(options, StreamContent::kTetMesh);
  return oneShot(OneShotAccess::impl(d), data, size, &d.tetMesh(), out);
}

}  // namespace mrsv
