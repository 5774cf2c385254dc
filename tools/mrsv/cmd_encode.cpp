// mrsv encode: raw samples in, an MRSV file out.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "cli.h"
#include "commands.h"
#include "mrsv/encode.h"
#include "mrsv/file_io.h"
#include "mrsv/raw_grid.h"

namespace mrsv::cli {
namespace {

const char kHelp[] =
    "Usage: mrsv encode [options] IN OUT.mrsv\n"
    "\n"
    "Encode a grid of samples (a terrain, an image, a volume) into an MRSV file.\n"
    "IN is a headerless raw file: x varies fastest, then y, then z.\n"
    "\n"
    "Input:\n"
    "  --dims X[,Y[,Z]]      grid size in samples (required)\n"
    "  --type T              sample type: uint8, int16, uint16, int32, float32, float64 (required)\n"
    "  --endian little|big   byte order of IN (default little)\n"
    "  --nodata V            sample value that marks missing data, e.g. -32768 for SRTM voids\n"
    "\n"
    "Coding:\n"
    "  --coding stored       stored: lossless, uncompressed (default; the only coding of format 0.1)\n"
    "\n"
    "Metadata (the meta chunk, spec 2.6):\n"
    "  --meta KEY=VALUE      add an entry; repeatable. Registered keys: value_units,\n"
    "                        spatial_units, spacing, origin, crs, provenance, description\n"
    "\n"
    "Other:\n"
    "  --quiet               no progress output\n"
    "  --help                this text\n"
    "\n"
    "OUT is written under a temporary name and renamed when complete; IN is never touched.\n"
    "Exit status: 0 done, 1 invalid input data, 2 usage error, 3 file error.\n";

// Converts the --nodata text to the sample type's bit pattern.
bool parseNodata(const std::string& text, SampleType type, uint64_t* bits, std::string* error) {
  char* end = nullptr;
  errno = 0;
  if (type == SampleType::kFloat32 || type == SampleType::kFloat64) {
    double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0') {
      *error = "--nodata '" + text + "' is not a number";
      return false;
    }
    if (type == SampleType::kFloat32) {
      float f = static_cast<float>(v);
      if (std::isfinite(v) && !std::isfinite(f)) {
        *error = "--nodata " + text + " is out of range for float32";
        return false;
      }
      uint32_t b;
      std::memcpy(&b, &f, 4);
      *bits = b;
    } else {
      std::memcpy(bits, &v, 8);
    }
    return true;
  }
  long long v = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno == ERANGE) {
    *error = "--nodata '" + text + "' is not a whole number";
    return false;
  }
  long long lo = 0, hi = 0;
  switch (type) {
    case SampleType::kUint8: lo = 0; hi = 255; break;
    case SampleType::kInt16: lo = -32768; hi = 32767; break;
    case SampleType::kUint16: lo = 0; hi = 65535; break;
    default: lo = std::numeric_limits<int32_t>::min(); hi = std::numeric_limits<int32_t>::max();
  }
  if (v < lo || v > hi) {
    *error = "--nodata " + text + " is out of range for " + sampleTypeName(type);
    return false;
  }
  uint64_t mask = sampleSize(type) == 8 ? ~uint64_t{0} : (uint64_t{1} << (8 * sampleSize(type))) - 1;
  *bits = static_cast<uint64_t>(v) & mask;
  return true;
}

}  // namespace

int runEncode(int argc, char** argv) {
  const char* cmd = "encode";
  Args args;
  std::string error;
  if (!args.parse(argc, argv,
                  {{"dims", "type", "endian", "nodata", "coding"}, {"quiet", "help"}, {"meta"}},
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
  if (!args.has("dims") || !args.has("type"))
    return fail(cmd, "raw input needs --dims and --type (see 'mrsv encode --help')", kExitUsage);

  GridHeader header;
  if (std::string problem = parseDims(args.value("dims"), &header); !problem.empty())
    return fail(cmd, "--dims: " + problem, kExitUsage);
  if (!parseSampleType(args.value("type"), &header.sample_type))
    return fail(cmd, "--type '" + args.value("type") +
                         "' is not one of uint8, int16, uint16, int32, float32, float64",
                kExitUsage);
  Endian endian = Endian::kLittle;
  if (args.has("endian")) {
    if (args.value("endian") == "big") endian = Endian::kBig;
    else if (args.value("endian") != "little")
      return fail(cmd, "--endian must be little or big", kExitUsage);
  }
  if (args.has("coding") && args.value("coding") != "stored")
    return fail(cmd, "--coding '" + args.value("coding") + "' is not known (format 0.1 has: stored)",
                kExitUsage);
  if (args.has("nodata")) {
    if (!parseNodata(args.value("nodata"), header.sample_type, &header.nodata_bits, &error))
      return fail(cmd, error, kExitUsage);
    header.grid_flags |= kGridFlagHasNodata;
  }
  Metadata metadata;
  for (const std::string& entry : args.values("meta")) {
    size_t eq = entry.find('=');
    if (eq == std::string::npos) return fail(cmd, "--meta '" + entry + "' is not KEY=VALUE", kExitUsage);
    std::string key = entry.substr(0, eq), value = entry.substr(eq + 1);
    if (std::string problem = metadataEntryProblem(key, value); !problem.empty())
      return fail(cmd, "--meta: " + problem, kExitUsage);
    if (metadata.find(key)) return fail(cmd, "--meta: key '" + key + "' given twice", kExitUsage);
    metadata.entries.emplace_back(key, value);
  }
  if (std::string problem = gridHeaderProblem(header); !problem.empty())
    return fail(cmd, "--dims: " + problem, kExitUsage);
  if (isSameFile(in, out)) return fail(cmd, "OUT is the same file as IN; refusing to overwrite the input", kExitUsage);

  Progress progress("encode", args.flag("quiet"));
  std::vector<uint8_t> samples;
  if (!readWholeFile(in, &samples, &error)) return fail(cmd, in + ": " + error, kExitIo);
  progress.update(0.3);
  uint64_t expected = header.sampleCount() * sampleSize(header.sample_type);
  if (samples.size() != expected)
    return fail(cmd, in + ": file has " + std::to_string(samples.size()) + " bytes but --dims " +
                         args.value("dims") + " --type " + args.value("type") + " needs " +
                         std::to_string(expected),
                kExitInvalidData);
  if (endian == Endian::kBig) swapSampleBytes(&samples, sampleSize(header.sample_type));

  std::vector<uint8_t> stream;
  Error e = encodeStoredGrid(header, samples, metadata, &stream);
  if (!e.ok()) return fail(cmd, in + ": " + e.field + ": " + e.message, kExitInvalidData);
  progress.update(0.7);
  if (!writeFileAtomically(out, stream, &error)) return fail(cmd, out + ": " + error, kExitIo);
  progress.update(1.0);
  return kExitOk;
}

}  // namespace mrsv::cli
