// mrsv decode --region: a box of a grid. A tiled stream (spec 11) is read
// through its index: only the tiles the box touches come off the disk.
#include <cstdio>
#include <memory>

#include "cli.h"
#include "commands.h"
#include "mrsv/file_io.h"
#include "mrsv/grid_formats.h"

namespace mrsv::cli {

int runRegionDecode(const Args& args, const std::string& in, const std::string& out,
                    const GridRegion& region, int threads, Endian endian, uint64_t levels,
                    ByteSource* source) {
  const char* cmd = "decode";
  std::string error;
  std::unique_ptr<ByteSource> file;
  if (source == nullptr) {
    file = openFileByteSource(in, &error);
    if (!file) return fail(cmd, in + ": " + error, kExitIo);
    source = file.get();
  }
  Progress progress("decode", args.flag("quiet"));
  DecodeOptions options;
  options.reduce_levels = static_cast<int>(levels);
  options.threads = threads;
  if (args.has("bytes")) options.container.allow_partial_tail = true;
  DecodedGrid grid;
  Error e = decodeGridRegion(*source, region, options, &grid);
  if (e.status == Status::kInvalidArgument) return fail(cmd, in + ": " + e.message, kExitUsage);
  if (!e.ok()) return reportError(cmd, in, e);
  if (grid.container.chunks.empty() || grid.container.chunks[0].chunk_type != kChunkGridHeader)
    return fail(cmd, in + ": --region is for grid streams", kExitUsage);
  progress.update(0.8);
  std::vector<uint8_t> output;
  if (args.flag("canonical")) {
    output = canonicalRegionOutput(grid);
  } else {
    if (!grid.has_samples)
      return fail(cmd, in + ": the stream ends before the region's sample data", kExitInvalidData);
    const Metadata metadata = decodedRegionMetadata(grid, region.lo, options.reduce_levels);
    if (!encodeGridOutput(out, grid.header, metadata, grid.output_size, std::move(grid.samples),
                          endian == Endian::kBig, &output, &error))
      return fail(cmd, error, kExitUsage);
  }
  if (!args.flag("quiet"))
    std::fprintf(stderr, "mrsv decode: %s: region %ux%ux%u, %llu of %llu bytes read%s\n", out.c_str(),
                 grid.output_size[0], grid.output_size[1], grid.output_size[2],
                 static_cast<unsigned long long>(source->bytesRead()),
                 static_cast<unsigned long long>(source->size()),
                 grid.header.coding == GridCoding::kTiled ? ""
                 : grid.region_by_precincts              ? " (precincts: the blocks the region reaches)"
                                                         : " (not tiled: the whole grid decoded)");
  if (!writeFileAtomically(out, output, &error)) return fail(cmd, out + ": " + error, kExitIo);
  progress.update(1.0);
  return kExitOk;
}

}  // namespace mrsv::cli
