// mrsv info (the chunk table of a file) and mrsv check (validation).
#include <cinttypes>
#include <cstdio>
#include <cstring>

#include "cli.h"
#include "common/byte_reader.h"
#include "commands.h"
#include "mrsv/file_io.h"
#include "mrsv/grid.h"
#include "mrsv/progressive_mesh.h"
#include "mrsv/progressive_tet_mesh.h"

namespace mrsv::cli {
namespace {

const char kInfoHelp[] =
    "Usage: mrsv info [--json] FILE.mrsv\n"
    "\n"
    "Print the format version, the content header, the chunk table (offset, type,\n"
    "payload length, CRC-32C; for a band also its index, its quantiser step in units\n"
    "of 2^-W and its prediction) and the metadata of an MRSV file. For a damaged file\n"
    "the chunks before the damage are listed, then the error.\n"
    "\n"
    "Options:\n"
    "  --json    machine-readable output\n"
    "  --help    this text\n"
    "\n"
    "Exit status: 0 valid, 1 invalid stream, 2 usage error, 3 file error.\n";

const char kCheckHelp[] =
    "Usage: mrsv check [--quiet] FILE.mrsv...\n"
    "\n"
    "Validate MRSV files against every rule a decoder applies: signature, version,\n"
    "chunk framing and checksums, chunk order, headers, metadata and sample data.\n"
    "Prints one line per file: 'FILE: ok ...' on stdout, or on stderr\n"
    "'FILE: offset N: E<code> <name>: <field>: <rule broken>'.\n"
    "\n"
    "Options:\n"
    "  --quiet   print only the files that fail\n"
    "  --help    this text\n"
    "\n"
    "Exit status: 0 all valid, 1 any invalid, 2 usage error, 3 file error.\n";

std::string chunkRole(const ChunkType& type) {
  if (type == kChunkGridHeader) return "grid header";
  if (type == kChunkGridStored) return "stored samples";
  if (type == kChunkMeta) return "metadata";
  if (type == kChunkWaveletHeader) return "wavelet header";
  if (type == kChunkTiling) return "tiling header";
  if (type == kChunkTileIndex) return "tile index";
  if (type == kChunkNodataMask) return "no-data mask";
  if (type == kChunkBand) return "band (coarse to fine)";
  if (type == kChunkResidual) return "residual layer";
  if (type == kChunkMeshHeader) return "mesh header";
  if (type == kChunkBaseMesh) return "base mesh";
  if (type == kChunkSplits) return "vertex-split batch (coarse to fine)";
  if (type == kChunkTetHeader) return "tet mesh header";
  if (type == kChunkTetBase) return "base tet mesh";
  if (type == kChunkTetSplits) return "tet vertex-split batch (coarse to fine)";
  if (type == kChunkEnd) return "end";
  return type.critical() ? "unknown critical" : "unknown ancillary (skipped)";
}

// The role of a chunk in the table, with a band's header (spec 5.3: index,
// step in units of 2^-W, prediction) read straight from its payload when it is
// long enough.
std::string chunkRoleText(const ChunkView& k) {
  std::string role = chunkRole(k.chunk_type);
  if (k.chunk_type != kChunkBand || k.chunk_length < 12 || k.payload == nullptr) return role;
  ByteReader r(k.payload, 12);  // band_index, band_flags, reserved, step
  const unsigned index = r.u16();
  const unsigned prediction = r.u8() & 3u;
  r.u8();
  const uint64_t step = r.u64();
  static const char* const kPrediction[4] = {"", ", neighbour prediction", ", weighted prediction",
                                             ", prediction 3 (reserved)"};
  char buf[96];
  std::snprintf(buf, sizeof buf, " #%u, step %" PRIu64 "%s", index, step, kPrediction[prediction]);
  return role + buf;
}

std::string nodataText(const GridHeader& h) {
  uint64_t b = h.nodata_bits;
  switch (h.sample_type) {
    case SampleType::kUint8:
    case SampleType::kUint16: return std::to_string(b);
    case SampleType::kInt16: return std::to_string(static_cast<int16_t>(b));
    case SampleType::kInt32: return std::to_string(static_cast<int32_t>(b));
    case SampleType::kFloat32: {
      float f;
      uint32_t u = static_cast<uint32_t>(b);
      std::memcpy(&f, &u, 4);
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.9g", f);
      return buf;
    }
    case SampleType::kFloat64: {
      double d;
      std::memcpy(&d, &b, 8);
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.17g", d);
      return buf;
    }
  }
  return "?";
}

std::string sizeText(const GridHeader& h) {
  std::string s = std::to_string(h.size_x);
  if (h.num_dims >= 2) s += "x" + std::to_string(h.size_y);
  if (h.num_dims >= 3) s += "x" + std::to_string(h.size_z);
  return s;
}

// What info prints of a file, whichever its content.
struct InfoView {
  const Container* container = nullptr;
  const Metadata* metadata = nullptr;
  std::string summary;       // one line
  std::string json_content;  // "  \"grid\": {...},\n" or "" when unreadable
};

std::string countText(const Container& c) {
  std::string s = ", " + std::to_string(c.chunks.size() + (c.complete ? 1 : 0)) + " chunks";
  return s + (c.complete ? ", complete" : ", prefix (ends before MEND)");
}

std::string summary(const DecodedGrid& grid) {
  if (grid.container.chunks.empty()) return "empty prefix (file header only)";
  const GridHeader& h = grid.header;
  if (h.num_dims == 0) return "content header not readable";
  std::string s = "grid " + std::to_string(h.num_dims) + "-D " + sampleTypeName(h.sample_type) +
                  " " + sizeText(h);
  if (h.coding == GridCoding::kStored) {
    s += ", stored";
  } else if (h.coding == GridCoding::kTiled) {
    s += ", tiled " + std::to_string(grid.tile_size[0]);
    for (int a = 1; a < h.num_dims; ++a) s += "x" + std::to_string(grid.tile_size[a]);
    s += " (" + std::to_string(grid.tiles_total) + " tiles, " + std::to_string(grid.tiles_with_samples) +
         " with samples), " + std::to_string(grid.bands_decoded) + "/" + std::to_string(grid.bands_total) +
         " bands";
  } else {
    const WaveletHeader& w = grid.wavelet;
    s += (w.order == kWaveletOrderCdf97 ? std::string(", wavelet CDF 9/7")
                                        : ", wavelet order " + std::to_string(w.order)) +
         ", levels " + std::to_string(w.levels[0]);
    for (int a = 1; a < h.num_dims; ++a) s += "/" + std::to_string(w.levels[a]);
    s += ", " + std::to_string(grid.bands_decoded) + "/" + std::to_string(grid.bands_total) + " bands";
    if (w.precinct_log2) s += ", precincts " + std::to_string(1u << w.precinct_log2);
    if (w.hasResidual()) s += grid.residual_decoded ? ", residual" : ", residual missing";
  }
  if (h.hasNodata()) s += ", nodata " + nodataText(h);
  return s + countText(grid.container);
}

InfoView gridView(const DecodedGrid& grid) {
  InfoView v{&grid.container, &grid.metadata, summary(grid), ""};
  const Container& c = grid.container;
  if (!c.chunks.empty() && c.chunks[0].chunk_type == kChunkGridHeader && grid.header.num_dims) {
    const GridHeader& h = grid.header;
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "  \"grid\": {\"num_dims\": %u, \"sample_type\": \"%s\", \"size\": [%u, %u, %u], "
                  "\"coding\": \"%s\", \"bands\": [%u, %u]",
                  h.num_dims, sampleTypeName(h.sample_type), h.size_x, h.size_y, h.size_z,
                  h.coding == GridCoding::kStored ? "stored" : h.coding == GridCoding::kTiled ? "tiled" : "wavelet",
                  grid.bands_decoded, grid.bands_total);
    v.json_content = buf;
    if (h.hasNodata()) v.json_content += ", \"nodata\": " + jsonString(nodataText(h));
    v.json_content += "},\n";
  }
  return v;
}

// spec 6.2: the PM header, and how much of the stream the bytes hold.
InfoView tetView(const DecodedTetMesh& mesh) {
  InfoView v{&mesh.container, &mesh.metadata, "", ""};
  const Container& c = mesh.container;
  if (c.chunks.empty()) {
    v.summary = "empty prefix (file header only)";
    return v;
  }
  const PtHeader& h = mesh.header;
  if (h.vertex_count == 0) {
    v.summary = "content header not readable";
    return v;
  }
  const uint32_t level = mesh.has_mesh ? mesh.mesh.splitsDecoded() : 0;
  char buf[768];
  std::snprintf(buf, sizeof buf,
                "progressive tet mesh, %u vertices, %u tets (base %u vertices, %u tets), %u splits in %u batches, "
                "%u-bit positions (step %g)",
                h.vertex_count, h.tet_count, h.base_vertex_count, h.base_tet_count, h.splitCount(), h.batch_count,
                h.position_bits, h.position_step);
  v.summary = buf;
  std::string fields_json;
  for (const PtField& f : h.fields) {
    v.summary += ", field '" + f.name + "' (" + std::to_string(f.bits) + " bits)";
    std::snprintf(buf, sizeof buf, "%s{\"name\": \"%s\", \"bits\": %u, \"origin\": %.17g, \"step\": %.17g}",
                  fields_json.empty() ? "" : ", ", f.name.c_str(), unsigned{f.bits}, f.origin, f.step);
    fields_json += buf;
  }
  v.summary += ", decoded " + std::to_string(mesh.batches_decoded) + "/" + std::to_string(h.batch_count) +
               " batches (" + std::to_string(level) + " splits)" + countText(c);
  std::snprintf(buf, sizeof buf,
                "  \"tets\": {\"vertex_count\": %u, \"tet_count\": %u, \"base_vertex_count\": %u, "
                "\"base_tet_count\": %u, \"batch_count\": %u, \"position_bits\": %u, \"position_step\": %.17g, "
                "\"origin\": [%.17g, %.17g, %.17g], \"batches_decoded\": %u, \"splits_decoded\": %u, \"fields\": [",
                h.vertex_count, h.tet_count, h.base_vertex_count, h.base_tet_count, h.batch_count, h.position_bits,
                h.position_step, h.origin[0], h.origin[1], h.origin[2], mesh.batches_decoded, level);
  v.json_content = buf + fields_json + "]},\n";
  return v;
}

InfoView meshView(const DecodedMesh& mesh) {
  InfoView v{&mesh.container, &mesh.metadata, "", ""};
  const Container& c = mesh.container;
  if (c.chunks.empty()) {
    v.summary = "empty prefix (file header only)";
    return v;
  }
  const PmHeader& h = mesh.header;
  if (h.vertex_count == 0) {
    v.summary = "content header not readable";
    return v;
  }
  const char* placement = h.placement == kPlacementFree ? "free" : "endpoint";
  const uint32_t level = mesh.has_mesh ? mesh.mesh.splitsDecoded() : 0;
  char buf[768];
  std::snprintf(buf, sizeof buf,
                "progressive mesh, %u vertices (base %u vertices, %u triangles), %u splits in %u batches, "
                "%u-bit positions (step %g), placement %s",
                h.vertex_count, h.base_vertex_count, h.base_triangle_count, h.splitCount(), h.batch_count,
                h.position_bits, h.position_step, placement);
  v.summary = buf;
  if (h.move_detail) v.summary += " (moves with " + std::to_string(h.move_detail) + " bits of detail)";
  if (h.scalar_bits) v.summary += ", " + std::to_string(h.scalar_bits) + "-bit scalar";
  v.summary += ", decoded " + std::to_string(mesh.batches_decoded) + "/" + std::to_string(h.batch_count) +
               " batches (" + std::to_string(level) + " splits)" + countText(c);
  std::snprintf(buf, sizeof buf,
                "  \"mesh\": {\"vertex_count\": %u, \"base_vertex_count\": %u, \"base_triangle_count\": %u, "
                "\"batch_count\": %u, \"position_bits\": %u, \"position_step\": %.17g, "
                "\"origin\": [%.17g, %.17g, %.17g], \"placement\": \"%s\", \"move_detail\": %u, \"scalar_bits\": %u, "
                "\"batches_decoded\": %u, \"splits_decoded\": %u},\n",
                h.vertex_count, h.base_vertex_count, h.base_triangle_count, h.batch_count, h.position_bits,
                h.position_step, h.origin[0], h.origin[1], h.origin[2], placement, h.move_detail, h.scalar_bits,
                mesh.batches_decoded, level);
  v.json_content = buf;
  return v;
}

void printJson(const std::string& file, size_t file_size, const InfoView& view, const Error& e) {
  const Container& c = *view.container;
  std::printf("{\n  \"file\": %s,\n  \"bytes\": %zu,\n", jsonString(file).c_str(), file_size);
  std::printf("  \"version\": \"%u.%u\",\n  \"complete\": %s,\n", c.version_major,
              c.version_minor, c.complete ? "true" : "false");
  std::fputs(view.json_content.c_str(), stdout);
  std::printf("  \"chunks\": [");
  for (size_t i = 0; i < c.chunks.size(); ++i) {
    const ChunkView& k = c.chunks[i];
    std::printf("%s\n    {\"offset\": %" PRIu64 ", \"type\": \"%s\", \"length\": %u, \"crc\": \"%08x\"}",
                i ? "," : "", k.offset, k.chunk_type.str().c_str(), k.chunk_length, k.chunk_crc);
  }
  if (c.complete)
    std::printf("%s\n    {\"offset\": %" PRIu64 ", \"type\": \"MEND\", \"length\": 0}",
                c.chunks.empty() ? "" : ",", c.end_chunk_offset);
  std::printf("\n  ],\n  \"metadata\": {");
  for (size_t i = 0; i < view.metadata->entries.size(); ++i)
    std::printf("%s%s: %s", i ? ", " : "", jsonString(view.metadata->entries[i].first).c_str(),
                jsonString(view.metadata->entries[i].second).c_str());
  std::printf("},\n  \"error\": ");
  if (e.ok()) {
    std::printf("null\n}\n");
  } else {
    std::printf("{\"code\": %d, \"name\": \"%s\", \"offset\": %" PRIu64 ", \"field\": %s, \"message\": %s}\n}\n",
                static_cast<int>(e.status), statusName(e.status), e.offset,
                jsonString(e.field).c_str(), jsonString(e.message).c_str());
  }
}

void printTable(const std::string& file, size_t file_size, const InfoView& view) {
  const Container& c = *view.container;
  std::printf("file:     %s (%zu bytes)\n", file.c_str(), file_size);
  std::printf("format:   MRSV %u.%u\n", c.version_major, c.version_minor);
  std::printf("content:  %s\n", view.summary.c_str());
  std::printf("chunks:\n  %10s  %-4s  %10s  %-8s  %s\n", "offset", "type", "length", "crc32c", "role");
  for (const ChunkView& k : c.chunks)
    std::printf("  %10" PRIu64 "  %-4s  %10u  %08x  %s\n", k.offset, k.chunk_type.str().c_str(), k.chunk_length,
                k.chunk_crc, chunkRoleText(k).c_str());
  if (c.complete)
    std::printf("  %10" PRIu64 "  %-4s  %10u  %-8s  %s\n", c.end_chunk_offset, "MEND", 0u, "", "end");
  if (!view.metadata->entries.empty()) {
    std::printf("metadata:\n");
    for (const auto& [key, value] : view.metadata->entries)
      std::printf("  %s=%s\n", key.c_str(), value.c_str());
  }
}

}  // namespace

int runInfo(int argc, char** argv) {
  const char* cmd = "info";
  Args args;
  std::string error;
  if (!args.parse(argc, argv, {{}, {"json", "help"}, {}}, &error))
    return fail(cmd, error + " (see 'mrsv info --help')", kExitUsage);
  if (args.flag("help")) {
    std::fputs(kInfoHelp, stdout);
    return kExitOk;
  }
  if (args.positional().size() != 1)
    return fail(cmd, "expected one FILE.mrsv (see 'mrsv info --help')", kExitUsage);
  const std::string& file = args.positional()[0];
  std::vector<uint8_t> bytes;
  if (!readWholeFile(file, &bytes, &error)) return fail(cmd, file + ": " + error, kExitIo);
  DecodedGrid grid;
  DecodedMesh mesh;
  DecodedTetMesh tets;
  Error e;
  InfoView view;
  if (isProgressiveTetStream(bytes.data(), bytes.size())) {
    e = decodeProgressiveTetMesh(bytes.data(), bytes.size(), DecodeOptions{}, &tets);
    view = tetView(tets);
  } else if (isProgressiveMeshStream(bytes.data(), bytes.size())) {
    e = decodeProgressiveMesh(bytes.data(), bytes.size(), DecodeOptions{}, &mesh);
    view = meshView(mesh);
  } else {
    e = decodeGrid(bytes.data(), bytes.size(), DecodeOptions{}, &grid);
    view = gridView(grid);
  }
  if (args.flag("json")) {
    printJson(file, bytes.size(), view, e);
    return e.ok() ? kExitOk : kExitInvalidData;
  }
  printTable(file, bytes.size(), view);
  return e.ok() ? kExitOk : reportError(cmd, file, e);
}

int runCheck(int argc, char** argv) {
  const char* cmd = "check";
  Args args;
  std::string error;
  if (!args.parse(argc, argv, {{}, {"quiet", "help"}, {}}, &error))
    return fail(cmd, error + " (see 'mrsv check --help')", kExitUsage);
  if (args.flag("help")) {
    std::fputs(kCheckHelp, stdout);
    return kExitOk;
  }
  if (args.positional().empty())
    return fail(cmd, "expected at least one FILE.mrsv (see 'mrsv check --help')", kExitUsage);
  int status = kExitOk;
  for (const std::string& file : args.positional()) {
    std::vector<uint8_t> bytes;
    if (!readWholeFile(file, &bytes, &error)) {
      fail(cmd, file + ": " + error, kExitIo);
      if (status == kExitOk) status = kExitIo;
      continue;
    }
    if (isProgressiveTetStream(bytes.data(), bytes.size())) {
      DecodedTetMesh decoded;
      Error e = decodeProgressiveTetMesh(bytes.data(), bytes.size(), DecodeOptions{}, &decoded);
      if (!e.ok()) {
        reportError(cmd, file, e);
        status = kExitInvalidData;
      } else if (!args.flag("quiet")) {
        const PtHeader& h = decoded.header;
        std::printf("%s: ok: progressive tet mesh, %u vertices, %u tets (base %u, %u tets), %u splits in %u "
                    "batches, every record checked; %u-bit positions, %zu fields%s\n",
                    file.c_str(), h.vertex_count, h.tet_count, h.base_vertex_count, h.base_tet_count, h.splitCount(),
                    h.batch_count, unsigned{h.position_bits}, h.fields.size(),
                    decoded.container.complete ? "" : "; a prefix (no MEND)");
      }
      continue;
    }
    if (isProgressiveMeshStream(bytes.data(), bytes.size())) {
      DecodedMesh decoded;
      Error e = decodeProgressiveMesh(bytes.data(), bytes.size(), DecodeOptions{}, &decoded);
      if (!e.ok()) {
        reportError(cmd, file, e);
        status = kExitInvalidData;
      } else if (!args.flag("quiet")) {
        const PmHeader& h = decoded.header;
        std::printf("%s: ok: progressive mesh, %u vertices (base %u, %u triangles), %u splits in %u batches, "
                    "every record checked; %u-bit positions%s%s\n",
                    file.c_str(), h.vertex_count, h.base_vertex_count, h.base_triangle_count, h.splitCount(),
                    h.batch_count, unsigned{h.position_bits}, h.scalar_bits ? ", scalar" : "",
                    decoded.container.complete ? "" : "; a prefix (no MEND)");
      }
      continue;
    }
    DecodedGrid grid;
    Error e = decodeGrid(bytes.data(), bytes.size(), DecodeOptions{}, &grid);
    if (!e.ok()) {
      reportError(cmd, file, e);
      status = kExitInvalidData;
    } else if (!args.flag("quiet")) {
      std::string recorded;
      for (const char* key : {"error_bound", "error_max_abs", "error_psnr_db", "error_rmse"})
        if (const std::string* v = grid.metadata.find(key))
          recorded += std::string(recorded.empty() ? "; recorded " : ", ") + key + "=" + *v;
      std::printf("%s: ok: %s%s\n", file.c_str(), summary(grid).c_str(), recorded.c_str());
    }
  }
  return status;
}

}  // namespace mrsv::cli
