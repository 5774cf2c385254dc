// Fuzz target: the grid file readers (NRRD, PGM P5/P2, SRTM .hgt, headerless
// raw) that `mrsv encode` and `mrsv tetrahedralize` run on user files. Readers
// must fail with one line naming the file, never crash; a grid they accept
// must have exactly its samples and metadata the encoder takes, and must come
// back unchanged through our NRRD (and, when it fits, PGM) writer.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "mrsv/grid_formats.h"
#include "mrsv/metadata.h"

namespace {

bool oneLineAboutFuzz(const std::string& error) {
  return error.rfind("fuzz: ", 0) == 0 && error.find('\n') == std::string::npos;
}

// Writes `in` as `name` and reads it back: the same sizes, type and samples.
void roundTrip(const char* name, mrsv::GridFormat format, const mrsv::GridInput& in) {
  const uint32_t size[3] = {in.header.size_x, in.header.size_y, in.header.size_z};
  for (bool big : {false, true}) {
    std::vector<uint8_t> file;
    std::string error;
    if (!mrsv::encodeGridOutput(name, in.header, in.metadata, size, in.samples, big, &file, &error)) std::abort();
    mrsv::GridInput back;
    if (!mrsv::readGridBytes("fuzz", format, mrsv::RawLayout{}, std::move(file), &back, &error)) std::abort();
    if (back.header.num_dims != in.header.num_dims || back.header.size_x != in.header.size_x ||
        back.header.size_y != in.header.size_y || back.header.size_z != in.header.size_z ||
        back.header.sample_type != in.header.sample_type || back.samples != in.samples)
      std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 3) return 0;
  // Byte 0 picks the format; for raw it also gives the sample type and byte
  // order, and bytes 1 and 2 the sizes (a 2-D grid of up to 256x256).
  static const mrsv::GridFormat kFormats[] = {mrsv::GridFormat::kRaw, mrsv::GridFormat::kNrrd,
                                              mrsv::GridFormat::kPgm, mrsv::GridFormat::kHgt};
  const mrsv::GridFormat format = kFormats[data[0] % 4];
  mrsv::RawLayout raw;
  size_t skip = 1;
  if (format == mrsv::GridFormat::kRaw) {
    raw.has_layout = true;
    raw.header.num_dims = 2;
    raw.header.size_x = 1u + data[1];
    raw.header.size_y = 1u + data[2];
    raw.header.sample_type = static_cast<mrsv::SampleType>(1 + (data[0] >> 2) % 6);
    raw.big_endian = (data[0] & 0x80) != 0;
    skip = 3;
  }
  mrsv::GridInput in;
  std::string error;
  if (!mrsv::readGridBytes("fuzz", format, raw, std::vector<uint8_t>(data + skip, data + size), &in,
                           &error)) {
    if (!oneLineAboutFuzz(error)) std::abort();
    return 0;
  }
  if (!mrsv::gridHeaderProblem(in.header).empty()) std::abort();
  if (in.samples.size() != in.header.sampleCount() * mrsv::sampleSize(in.header.sample_type)) std::abort();
  for (const auto& [key, value] : in.metadata.entries)
    if (!mrsv::metadataEntryProblem(key, value).empty()) std::abort();
  roundTrip("out.nrrd", mrsv::GridFormat::kNrrd, in);
  if (in.header.num_dims == 2 && (in.header.sample_type == mrsv::SampleType::kUint8 ||
                                  in.header.sample_type == mrsv::SampleType::kUint16))
    roundTrip("out.pgm", mrsv::GridFormat::kPgm, in);
  return 0;
}
