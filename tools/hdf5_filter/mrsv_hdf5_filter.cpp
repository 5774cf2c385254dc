// The MRSV HDF5 filter plugin (issue 24, spec Annex C): each chunk of a
// dataset is stored as one complete MRSV grid stream, lossless or lossy as
// `mrsv encode` codes it. HDF5 loads the plugin from HDF5_PLUGIN_PATH through
// H5PLget_plugin_type and H5PLget_plugin_info.
//
// set_local turns what the user gave (nothing, {mode} or {mode, parameter})
// into the stored cd_values of Annex C.2: mode, parameter, sample type, the
// no-data value and the chunk dims, so that the filter function needs nothing
// but the cd_values in both directions. Every failure pushes an HDF5 error
// naming the rule broken and returns 0 (the filter) or -1 (set_local); no C++
// exception crosses into HDF5.
#include <hdf5.h>
#include <H5PLextern.h>

#include <cstdint>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "mrsv/container.h"
#include "mrsv/encode.h"
#include "mrsv/grid.h"
#include "mrsv/limits.h"
#include "mrsv_hdf5_filter.h"

namespace {

using mrsv::GridHeader;
using mrsv::SampleType;

constexpr int kMaxRank = 32;  // H5S_MAX_RANK
constexpr size_t kMaxCdValues = MRSV_H5Z_CD_DIMS + kMaxRank;

void pushError(const char* function, const std::string& message) {
  H5Epush2(H5E_DEFAULT, __FILE__, function, __LINE__, H5E_ERR_CLS, H5E_PLINE, H5E_CANTFILTER, "%s",
           ("MRSV filter: " + message).c_str());
}

bool isFloat(SampleType t) { return t == SampleType::kFloat32 || t == SampleType::kFloat64; }

// The mode's parameter range: that of the matching `mrsv encode` option.
std::string parameterProblem(unsigned mode, double value) {
  switch (mode) {
    case MRSV_H5Z_MODE_LOSSLESS: return {};
    case MRSV_H5Z_MODE_RATE:
      return value >= 1e-3 && value <= 64 ? "" : "rate must be 0.001 to 64 bits per sample";
    case MRSV_H5Z_MODE_PSNR: return value >= 1 && value <= 400 ? "" : "PSNR must be 1 to 400 dB";
    case MRSV_H5Z_MODE_MAX_ERROR:
      return value >= 0 && value <= 524287 ? "" : "max error must be 0 to 524287 sample units";
    default: return "mode " + std::to_string(mode) + " is not 0 (lossless), 1 (rate), 2 (PSNR) or 3 (max error)";
  }
}

double doubleFromWords(unsigned lo, unsigned hi) {
  uint64_t bits = (uint64_t{hi} << 32) | lo;
  double v;
  std::memcpy(&v, &bits, 8);
  return v;
}

// "int16", "uint32", "float32 big-endian", "compound", ...: the HDF5 type as
// the refusal names it.
std::string typeName(hid_t type) {
  H5T_class_t cls = H5Tget_class(type);
  size_t bits = 8 * H5Tget_size(type);
  std::string name;
  switch (cls) {
    case H5T_INTEGER:
      name = (H5Tget_sign(type) == H5T_SGN_NONE ? "uint" : "int") + std::to_string(bits);
      break;
    case H5T_FLOAT: name = "float" + std::to_string(bits); break;
    case H5T_STRING: return "string";
    case H5T_BITFIELD: return "bitfield";
    case H5T_OPAQUE: return "opaque";
    case H5T_COMPOUND: return "compound";
    case H5T_REFERENCE: return "reference";
    case H5T_ENUM: return "enum";
    case H5T_VLEN: return "variable-length";
    case H5T_ARRAY: return "array";
    default: return "class " + std::to_string(static_cast<int>(cls));
  }
  if (H5Tget_order(type) == H5T_ORDER_BE) name += " big-endian";
  if (H5Tget_precision(type) != bits || H5Tget_offset(type) != 0) name += " with padding bits";
  return name;
}

// The MRSV sample type of an HDF5 element type, or false.
bool sampleTypeOf(hid_t type, SampleType* out) {
  H5T_class_t cls = H5Tget_class(type);
  size_t size = H5Tget_size(type);
  if ((cls != H5T_INTEGER && cls != H5T_FLOAT) || H5Tget_order(type) != H5T_ORDER_LE ||
      H5Tget_precision(type) != 8 * size || H5Tget_offset(type) != 0)
    return false;
  if (cls == H5T_FLOAT) {
    // IEEE binary32/64 layouts only (HDF5 also describes other float formats).
    size_t spos, epos, esize, mpos, msize;
    if (H5Tget_fields(type, &spos, &epos, &esize, &mpos, &msize) < 0) return false;
    if (size == 4 && spos == 31 && esize == 8 && msize == 23) *out = SampleType::kFloat32;
    else if (size == 8 && spos == 63 && esize == 11 && msize == 52) *out = SampleType::kFloat64;
    else return false;
    return true;
  }
  bool is_signed = H5Tget_sign(type) != H5T_SGN_NONE;
  if (size == 1 && !is_signed) *out = SampleType::kUint8;
  else if (size == 2 && is_signed) *out = SampleType::kInt16;
  else if (size == 2) *out = SampleType::kUint16;
  else if (size == 4 && is_signed) *out = SampleType::kInt32;
  else return false;
  return true;
}

// What the stored cd_values say (Annex C.2), checked.
struct FilterParams {
  unsigned mode = MRSV_H5Z_MODE_LOSSLESS;
  double parameter = 0;
  GridHeader header;       // num_dims, sizes, sample type and no-data of every chunk
  uint64_t chunk_bytes = 0;
};

// Annex C.3: leading chunk dims of 1 are dropped (at least one dim stays);
// what remains, fastest first, is x, y, z and must be at most 3 dims.
std::string gridOfChunk(int rank, const unsigned* dims, GridHeader* header) {
  int first = 0;
  while (first < rank - 1 && dims[first] == 1) ++first;
  int grid_rank = rank - first;
  if (grid_rank > 3)
    return "chunks of rank " + std::to_string(rank) + " with " + std::to_string(grid_rank) +
           " dims beyond leading 1s are not supported (at most 3: x, y, z)";
  header->num_dims = static_cast<uint8_t>(grid_rank);
  uint32_t* sizes[3] = {&header->size_x, &header->size_y, &header->size_z};
  for (int a = 0; a < 3; ++a) *sizes[a] = a < grid_rank ? dims[rank - 1 - a] : 1;
  return mrsv::gridHeaderProblem(*header);
}

std::string parseCdValues(size_t n, const unsigned* cd, FilterParams* p) {
  if (n < MRSV_H5Z_CD_DIMS + 1) return "cd_values has " + std::to_string(n) + " values, fewer than 10";
  if (cd[MRSV_H5Z_CD_VERSION] != MRSV_H5Z_CD_VERSION_VALUE)
    return "cd_values version " + std::to_string(cd[MRSV_H5Z_CD_VERSION]) + " is not 1";
  p->mode = cd[MRSV_H5Z_CD_MODE];
  p->parameter = doubleFromWords(cd[MRSV_H5Z_CD_PARAM_LO], cd[MRSV_H5Z_CD_PARAM_HI]);
  if (std::string problem = parameterProblem(p->mode, p->parameter); !problem.empty()) return problem;
  if (!mrsv::isValidSampleType(static_cast<uint8_t>(cd[MRSV_H5Z_CD_SAMPLE_TYPE])) ||
      cd[MRSV_H5Z_CD_SAMPLE_TYPE] > 255)
    return "sample type " + std::to_string(cd[MRSV_H5Z_CD_SAMPLE_TYPE]) + " is not 1 to 6";
  p->header.sample_type = static_cast<SampleType>(cd[MRSV_H5Z_CD_SAMPLE_TYPE]);
  if (cd[MRSV_H5Z_CD_FLAGS] & ~MRSV_H5Z_CD_FLAG_NODATA) return "reserved flag bits are set";
  if (cd[MRSV_H5Z_CD_FLAGS] & MRSV_H5Z_CD_FLAG_NODATA) {
    p->header.grid_flags = mrsv::kGridFlagHasNodata;
    p->header.nodata_bits = (uint64_t{cd[MRSV_H5Z_CD_NODATA_HI]} << 32) | cd[MRSV_H5Z_CD_NODATA_LO];
  } else if (cd[MRSV_H5Z_CD_NODATA_LO] != 0 || cd[MRSV_H5Z_CD_NODATA_HI] != 0) {
    return "no-data bits are set without the no-data flag";
  }
  unsigned rank = cd[MRSV_H5Z_CD_RANK];
  if (rank < 1 || rank > kMaxRank || n != MRSV_H5Z_CD_DIMS + rank)
    return "rank " + std::to_string(rank) + " does not match the " + std::to_string(n) + " cd_values";
  for (unsigned i = 0; i < rank; ++i)
    if (cd[MRSV_H5Z_CD_DIMS + i] == 0) return "chunk dim " + std::to_string(i) + " is 0";
  if (std::string problem = gridOfChunk(static_cast<int>(rank), cd + MRSV_H5Z_CD_DIMS, &p->header);
      !problem.empty())
    return problem;
  p->chunk_bytes = p->header.sampleCount() * mrsv::sampleSize(p->header.sample_type);
  return {};
}

// ---- set_local: records the dataset's type, chunk and no-data ----------------

herr_t setLocal(hid_t dcpl, hid_t type, hid_t /*space*/) {
  const char* fn = "mrsv_set_local";
  try {
    unsigned flags = 0;
    size_t n = kMaxCdValues;
    unsigned cd[kMaxCdValues] = {};
    if (H5Pget_filter_by_id2(dcpl, MRSV_H5Z_FILTER_ID, &flags, &n, cd, 0, nullptr, nullptr) < 0) {
      pushError(fn, "cannot read the filter's parameters");
      return -1;
    }
    // What the user gave: {}, {mode} or {mode, lo, hi}; a copied dataset's
    // creation properties hold the stored form (10 or more values).
    unsigned mode = MRSV_H5Z_MODE_LOSSLESS, lo = 0, hi = 0;
    if (n == 1) {
      mode = cd[0];
    } else if (n == 3) {
      mode = cd[0], lo = cd[1], hi = cd[2];
    } else if (n > MRSV_H5Z_CD_DIMS && cd[MRSV_H5Z_CD_VERSION] == MRSV_H5Z_CD_VERSION_VALUE) {
      mode = cd[MRSV_H5Z_CD_MODE], lo = cd[MRSV_H5Z_CD_PARAM_LO], hi = cd[MRSV_H5Z_CD_PARAM_HI];
    } else if (n != 0) {
      pushError(fn, "give no cd_values (lossless), {mode} or {mode, parameter low word, high word}, not " +
                        std::to_string(n) + " values");
      return -1;
    }
    if (mode == MRSV_H5Z_MODE_LOSSLESS) lo = hi = 0;
    if (std::string problem = parameterProblem(mode, doubleFromWords(lo, hi)); !problem.empty()) {
      pushError(fn, problem);
      return -1;
    }
    SampleType sample_type;
    if (!sampleTypeOf(type, &sample_type)) {
      pushError(fn, "element type " + typeName(type) +
                        " is not supported (uint8, int16, uint16, int32, float32, float64, little-endian)");
      return -1;
    }
    if (isFloat(sample_type) && mode == MRSV_H5Z_MODE_MAX_ERROR) {
      pushError(fn, std::string("a max error bound needs integer samples, not ") +
                        mrsv::sampleTypeName(sample_type) + " (use mode rate or PSNR)");
      return -1;
    }
    hsize_t dims[kMaxRank];
    int rank = H5Pget_chunk(dcpl, kMaxRank, dims);
    if (rank < 1) {
      pushError(fn, "the dataset is not chunked");
      return -1;
    }
    unsigned stored[kMaxCdValues] = {};
    stored[MRSV_H5Z_CD_VERSION] = MRSV_H5Z_CD_VERSION_VALUE;
    stored[MRSV_H5Z_CD_MODE] = mode;
    stored[MRSV_H5Z_CD_PARAM_LO] = lo;
    stored[MRSV_H5Z_CD_PARAM_HI] = hi;
    stored[MRSV_H5Z_CD_SAMPLE_TYPE] = static_cast<unsigned>(sample_type);
    stored[MRSV_H5Z_CD_RANK] = static_cast<unsigned>(rank);
    for (int i = 0; i < rank; ++i) {
      if (dims[i] > mrsv::kMaxGridAxis) {
        pushError(fn, "chunk dim " + std::to_string(i) + " (" + std::to_string(dims[i]) +
                          ") exceeds MRSV's axis limit of " + std::to_string(mrsv::kMaxGridAxis));
        return -1;
      }
      stored[MRSV_H5Z_CD_DIMS + i] = static_cast<unsigned>(dims[i]);
    }
    // A user-defined fill value marks no-data (Annex C.4): HDF5 pads edge
    // chunks with it, and the decoder restores those samples exactly.
    H5D_fill_value_t fill_status;
    if (H5Pfill_value_defined(dcpl, &fill_status) >= 0 && fill_status == H5D_FILL_VALUE_USER_DEFINED) {
      uint8_t fill[8] = {};
      if (H5Pget_fill_value(dcpl, type, fill) >= 0) {
        uint64_t bits = 0;
        for (size_t b = mrsv::sampleSize(sample_type); b-- > 0;) bits = (bits << 8) | fill[b];
        stored[MRSV_H5Z_CD_FLAGS] = MRSV_H5Z_CD_FLAG_NODATA;
        stored[MRSV_H5Z_CD_NODATA_LO] = static_cast<unsigned>(bits & 0xffffffffu);
        stored[MRSV_H5Z_CD_NODATA_HI] = static_cast<unsigned>(bits >> 32);
      }
    }
    size_t stored_n = MRSV_H5Z_CD_DIMS + static_cast<size_t>(rank);
    FilterParams check;
    if (std::string problem = parseCdValues(stored_n, stored, &check); !problem.empty()) {
      pushError(fn, problem);
      return -1;
    }
    if (H5Pmodify_filter(dcpl, MRSV_H5Z_FILTER_ID, flags, stored_n, stored) < 0) {
      pushError(fn, "cannot store the filter's parameters");
      return -1;
    }
    return 1;
  } catch (const std::exception& e) {
    pushError(fn, e.what());
    return -1;
  }
}

// ---- the filter: one chunk in, one MRSV stream out, and back ----------------

// Hands `bytes` to HDF5 in place of its buffer.
size_t replaceBuffer(const uint8_t* bytes, size_t size, size_t* buf_size, void** buf) {
  void* out = H5allocate_memory(size, false);
  if (out == nullptr) {
    pushError("mrsv_filter", "out of memory for " + std::to_string(size) + " bytes");
    return 0;
  }
  std::memcpy(out, bytes, size);
  H5free_memory(*buf);
  *buf = out;
  *buf_size = size;
  return size;
}

// The stream without its meta chunk: the encoder records its measured error
// there (about 80 bytes with framing), which no HDF5 reader needs; without it
// a chunk is only smaller, so a rate target stays met.
mrsv::Error dropMetaChunk(std::vector<uint8_t>* stream) {
  mrsv::Container container;
  if (mrsv::Error e = mrsv::readContainer(stream->data(), stream->size(), mrsv::ContainerOptions{}, &container);
      !e.ok())
    return e;
  mrsv::ContainerWriter writer;
  for (const mrsv::ChunkView& chunk : container.chunks) {
    if (chunk.chunk_type.str() == "meta") continue;
    writer.addChunk(chunk.chunk_type, std::vector<uint8_t>(chunk.payload, chunk.payload + chunk.chunk_length));
  }
  *stream = writer.finish();
  return {};
}

size_t encodeChunk(const FilterParams& p, size_t nbytes, size_t* buf_size, void** buf) {
  const char* fn = "mrsv_filter";
  if (nbytes != p.chunk_bytes) {
    pushError(fn, "a chunk of " + std::to_string(nbytes) + " bytes, not the " + std::to_string(p.chunk_bytes) +
                      " of the chunk dims");
    return 0;
  }
  const uint8_t* in = static_cast<const uint8_t*>(*buf);
  std::vector<uint8_t> samples(in, in + nbytes);
  GridHeader header = p.header;
  std::vector<uint8_t> stream;
  mrsv::Error e;
  if (p.mode == MRSV_H5Z_MODE_LOSSLESS && isFloat(header.sample_type)) {
    // The wavelet coder is exact only for integer samples: floats are stored.
    header.coding = mrsv::GridCoding::kStored;
    e = mrsv::encodeStoredGrid(header, samples, mrsv::Metadata{}, &stream);
  } else {
    header.coding = mrsv::GridCoding::kWavelet;
    mrsv::WaveletEncodeOptions options;
    switch (p.mode) {
      case MRSV_H5Z_MODE_LOSSLESS: options.max_error = 0; break;
      case MRSV_H5Z_MODE_RATE: options.bits_per_sample = p.parameter; break;
      case MRSV_H5Z_MODE_PSNR: options.psnr = p.parameter; break;
      default: options.max_error = p.parameter; break;
    }
    e = mrsv::encodeWaveletGrid(header, samples, mrsv::Metadata{}, options, &stream, nullptr);
    if (e.ok()) e = dropMetaChunk(&stream);
  }
  if (!e.ok()) {
    pushError(fn, "encoding a chunk: " + e.field + ": " + e.message);
    return 0;
  }
  return replaceBuffer(stream.data(), stream.size(), buf_size, buf);
}

size_t decodeChunk(const FilterParams& p, size_t nbytes, size_t* buf_size, void** buf) {
  const char* fn = "mrsv_filter";
  const uint8_t* in = static_cast<const uint8_t*>(*buf);
  // The grid header first: a stream for another chunk shape or type is
  // refused before the decoder allocates anything for it.
  mrsv::Container container;
  mrsv::Error e = mrsv::readContainer(in, nbytes, mrsv::ContainerOptions{}, &container);
  GridHeader header;
  if (e.ok() && (container.chunks.empty() || container.chunks[0].chunk_type.str() != "GHDR"))
    e = mrsv::Error{mrsv::Status::kBadGridHeader, 0, "GHDR", "the stream is not a grid"};
  if (e.ok()) e = mrsv::parseGridHeader(container.chunks[0], &header);
  if (!e.ok()) {
    pushError(fn, "reading a chunk's stream (" + std::to_string(nbytes) + " bytes): " + e.describe());
    return 0;
  }
  if (header.num_dims != p.header.num_dims || header.size_x != p.header.size_x ||
      header.size_y != p.header.size_y || header.size_z != p.header.size_z ||
      header.sample_type != p.header.sample_type) {
    pushError(fn, "a chunk's stream holds a " + std::to_string(header.size_x) + "x" + std::to_string(header.size_y) +
                      "x" + std::to_string(header.size_z) + " " + mrsv::sampleTypeName(header.sample_type) +
                      " grid, not the dataset's chunk of " + std::to_string(p.header.size_x) + "x" +
                      std::to_string(p.header.size_y) + "x" + std::to_string(p.header.size_z) + " " +
                      mrsv::sampleTypeName(p.header.sample_type));
    return 0;
  }
  mrsv::DecodedGrid grid;
  e = mrsv::decodeGrid(in, nbytes, mrsv::DecodeOptions{}, &grid);
  if (e.ok() && !grid.container.complete)
    e = mrsv::Error{mrsv::Status::kTruncatedChunkHeader, nbytes, "MEND", "the stream ends before MEND"};
  if (e.ok() && grid.samples.size() != p.chunk_bytes)
    e = mrsv::Error{mrsv::Status::kSampleDataMismatch, 0, "samples",
                    std::to_string(grid.samples.size()) + " bytes decoded, not the chunk's " +
                        std::to_string(p.chunk_bytes)};
  if (!e.ok()) {
    pushError(fn, "decoding a chunk's stream (" + std::to_string(nbytes) + " bytes): " + e.describe());
    return 0;
  }
  return replaceBuffer(grid.samples.data(), grid.samples.size(), buf_size, buf);
}

size_t filter(unsigned flags, size_t cd_nelmts, const unsigned cd_values[], size_t nbytes, size_t* buf_size,
              void** buf) {
  try {
    FilterParams p;
    if (std::string problem = parseCdValues(cd_nelmts, cd_values, &p); !problem.empty()) {
      pushError("mrsv_filter", "the dataset's filter parameters: " + problem);
      return 0;
    }
    return (flags & H5Z_FLAG_REVERSE) ? decodeChunk(p, nbytes, buf_size, buf)
                                      : encodeChunk(p, nbytes, buf_size, buf);
  } catch (const std::exception& e) {
    pushError("mrsv_filter", e.what());
    return 0;
  }
}

const H5Z_class2_t kFilterClass = {
    H5Z_CLASS_T_VERS,
    static_cast<H5Z_filter_t>(MRSV_H5Z_FILTER_ID),
    1,  // encoder present
    1,  // decoder present
    "mrsv: MRSV grid stream per chunk",
    nullptr,  // can_apply: set_local checks and names what it refuses
    setLocal,
    filter,
};

}  // namespace

extern "C" {
H5PL_type_t H5PLget_plugin_type(void) { return H5PL_TYPE_FILTER; }
const void* H5PLget_plugin_info(void) { return &kFilterClass; }
}
