// Grid file formats of the tools: headerless raw, NRRD (attached, raw
// encoding), PGM (P5 binary or P2 plain, 8 or 16 bit), SRTM .hgt, and rasters
// through GDAL (gdal_grid.cpp) in builds that have it.
#include "mrsv/grid_formats.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>

#include "io/gdal_grid.h"
#include "io/number_list.h"
#include "mrsv/file_io.h"
#include "mrsv/metadata.h"
#include "mrsv/raw_grid.h"

namespace mrsv {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && lower(s.substr(s.size() - suffix.size())) == suffix;
}

std::string trim(const std::string& s) {
  size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

bool nrrdType(const std::string& t, SampleType* out) {
  static const struct {
    const char* name;
    SampleType type;
  } kTypes[] = {
      {"uchar", SampleType::kUint8},          {"unsigned char", SampleType::kUint8},
      {"uint8", SampleType::kUint8},          {"uint8_t", SampleType::kUint8},
      {"short", SampleType::kInt16},          {"short int", SampleType::kInt16},
      {"signed short", SampleType::kInt16},   {"signed short int", SampleType::kInt16},
      {"int16", SampleType::kInt16},          {"int16_t", SampleType::kInt16},
      {"ushort", SampleType::kUint16},        {"unsigned short", SampleType::kUint16},
      {"unsigned short int", SampleType::kUint16}, {"uint16", SampleType::kUint16},
      {"uint16_t", SampleType::kUint16},      {"int", SampleType::kInt32},
      {"signed int", SampleType::kInt32},     {"int32", SampleType::kInt32},
      {"int32_t", SampleType::kInt32},        {"float", SampleType::kFloat32},
      {"double", SampleType::kFloat64},
  };
  for (const auto& k : kTypes)
    if (t == k.name) {
      *out = k.type;
      return true;
    }
  return false;
}

const char* nrrdTypeName(SampleType t) {
  switch (t) {
    case SampleType::kUint8: return "uint8";
    case SampleType::kInt16: return "int16";
    case SampleType::kUint16: return "uint16";
    case SampleType::kInt32: return "int32";
    case SampleType::kFloat32: return "float";
    case SampleType::kFloat64: return "double";
  }
  return "?";
}

// A header value as shown in an error: control bytes (a binary file read as
// a header) would break the one-line message, and a long value hides the rest.
std::string shown(const std::string& s) {
  std::string out;
  for (char c : s.substr(0, 40))
    out += (c >= 0x20 && c < 0x7F) ? c : '?';
  return s.size() > 40 ? out + "..." : out;
}

// "(1,0,0) (0,1,0)" or "1 1 2" → the numbers in order; NRRD writes vectors in
// parentheses, with or without spaces after the commas.
std::vector<std::string> numberTokens(const std::string& text) {
  std::vector<std::string> out;
  std::string token;
  for (char c : text + " ") {
    if (c == '(' || c == ')' || c == ',' || c == ' ' || c == '\t') {
      if (!token.empty()) out.push_back(token);
      token.clear();
    } else {
      token += c;
    }
  }
  return out;
}

// A spacing or origin list for the meta chunk ("1,1,2"): empty when NRRD says
// the value is unknown (nan); `problem` is set when it is not `count` numbers.
std::string metaNumberList(const std::string& key, const std::string& text, size_t count,
                           std::string* problem) {
  problem->clear();
  std::vector<std::string> tokens = numberTokens(text);
  std::string joined;
  for (const std::string& t : tokens) {
    if (lower(t) == "nan" || lower(t) == "none") return {};
    joined += (joined.empty() ? "" : ",") + t;
  }
  if (tokens.size() != count) {
    *problem = "has " + std::to_string(tokens.size()) + " numbers, not one per axis (" +
               std::to_string(count) + ")";
  } else if (!metadataEntryProblem(key, joined).empty()) {
    *problem = "'" + shown(text) + "' is not a list of decimal numbers";
  }
  return joined;
}

// NRRD (teem's format, versions NRRD0001 to NRRD0005) with the data attached
// after the header's blank line. Only what changes the samples must be
// understood; descriptive fields (kinds, units, labels, ...) are skipped.
bool readNrrd(const std::string& path, const std::vector<uint8_t>& bytes, GridInput* in,
              std::string* error) {
  size_t pos = 0;
  int line_number = 0;
  auto line = [&](std::string* out) {
    if (pos >= bytes.size()) return false;
    size_t end = pos;
    while (end < bytes.size() && bytes[end] != '\n') ++end;
    *out = std::string(reinterpret_cast<const char*>(bytes.data() + pos), end - pos);
    if (!out->empty() && out->back() == '\r') out->pop_back();
    pos = end + 1;
    ++line_number;
    return true;
  };
  auto fail = [&](int at, const std::string& problem) {
    *error = path + ": line " + std::to_string(at) + ": " + problem;
    return false;
  };
  std::string text;
  if (!line(&text) || text.size() != 8 || text.compare(0, 7, "NRRD000") != 0 || text[7] < '1' ||
      text[7] > '5') {
    *error = path + ": line 1: not an NRRD file (the first line must be NRRD0001 to NRRD0005)";
    return false;
  }
  struct Field {
    std::string value;
    int line = 0;
  };
  Field type, encoding, endian, dimension, sizes, spacings, origin;
  bool ended = false;
  while (line(&text)) {
    if (text.empty()) {
      ended = true;
      break;
    }
    if (text[0] == '#') continue;
    size_t colon = text.find(':');
    if (colon == std::string::npos)
      return fail(line_number, "'" + shown(text) + "' is not a comment or a 'field: value' line");
    if (colon + 1 < text.size() && text[colon + 1] == '=') continue;  // key:=value pairs
    std::string key = lower(trim(text.substr(0, colon)));
    Field field{trim(text.substr(colon + 1)), line_number};
    if (key == "type") type = field;
    else if (key == "encoding") encoding = field;
    else if (key == "endian") endian = field;
    else if (key == "dimension") dimension = field;
    else if (key == "sizes") sizes = field;
    else if (key == "spacings") spacings = field;
    else if (key == "space origin") origin = field;
    else if (key == "data file" || key == "datafile")
      return fail(line_number, "field 'data file': detached data is not supported; attach it (unu save)");
    else if ((key == "line skip" || key == "lineskip" || key == "byte skip" || key == "byteskip") &&
             field.value != "0")
      return fail(line_number, "field '" + key + "' " + shown(field.value) +
                                   " is not supported (only 0: the data follows the header)");
  }
  if (!ended)
    return fail(line_number, "the header does not end with a blank line before the data");
  for (const auto& [name, field] : {std::pair<const char*, const Field*>{"type", &type},
                                    {"dimension", &dimension}, {"sizes", &sizes}})
    if (field->line == 0) return fail(line_number, std::string("the header has no '") + name + "' field");
  if (!nrrdType(lower(type.value), &in->header.sample_type))
    return fail(type.line, "field 'type' '" + shown(type.value) +
                               "' is not one of uint8, int16, uint16, int32, float, double");
  std::string enc = encoding.line ? lower(encoding.value) : "raw";
  if (enc != "raw")
    return fail(encoding.line, "field 'encoding' '" + shown(encoding.value) +
                                   "' is not supported (only raw; unu save -e raw converts)");
  const size_t sample_size = sampleSize(in->header.sample_type);
  std::string end = lower(endian.value);
  if (endian.line == 0 && sample_size > 1)
    return fail(line_number, "the header has no 'endian' field, which " +
                                 std::string(nrrdTypeName(in->header.sample_type)) + " data needs");
  if (endian.line != 0 && end != "little" && end != "big")
    return fail(endian.line, "field 'endian' '" + shown(endian.value) + "' is not little or big");
  if (dimension.value.size() != 1 || dimension.value[0] < '1' || dimension.value[0] > '3')
    return fail(dimension.line, "field 'dimension' '" + shown(dimension.value) +
                                    "' is not 1, 2 or 3 (MRSV grids have 1 to 3 axes)");
  const size_t dims = static_cast<size_t>(dimension.value[0] - '0');
  std::vector<std::string> size_tokens = numberTokens(sizes.value);
  std::string joined;
  for (const std::string& t : size_tokens) joined += (joined.empty() ? "" : ",") + t;
  if (size_tokens.size() != dims)
    return fail(sizes.line, "field 'sizes' has " + std::to_string(size_tokens.size()) +
                                " numbers, not 'dimension' (" + std::to_string(dims) + ")");
  if (std::string problem = parseDims(joined, &in->header); !problem.empty())
    return fail(sizes.line, "field 'sizes': " + shown(problem));
  std::string problem;
  std::string spacing = metaNumberList("spacing", spacings.value, dims, &problem);
  if (spacings.line && !problem.empty()) return fail(spacings.line, "field 'spacings' " + problem);
  std::string place = metaNumberList("origin", origin.value, dims, &problem);
  if (origin.line && !problem.empty()) return fail(origin.line, "field 'space origin' " + problem);
  in->samples.assign(bytes.begin() + static_cast<long>(std::min(pos, bytes.size())), bytes.end());
  if (end == "big") swapSampleBytes(&in->samples, sample_size);
  if (spacings.line && !spacing.empty()) in->metadata.set("spacing", spacing);
  if (origin.line && !place.empty()) in->metadata.set("origin", place);
  return true;
}

// Netpbm PGM: P5 (binary; 16-bit samples most significant byte first) or P2
// (plain: decimal samples). Samples are kept as stored, not scaled to maxval.
bool readPgm(const std::string& path, const std::vector<uint8_t>& bytes, GridInput* in,
             std::string* error) {
  auto fail = [&](size_t at, const std::string& problem) {
    *error = path + ": offset " + std::to_string(at) + ": " + problem;
    return false;
  };
  size_t pos = 2;
  auto skipSpace = [&] {
    while (pos < bytes.size()) {
      if (bytes[pos] == '#') {
        while (pos < bytes.size() && bytes[pos] != '\n') ++pos;
      } else if (std::isspace(bytes[pos])) {
        ++pos;
      } else {
        break;
      }
    }
  };
  // Skips white space and '#' comments, then reads a decimal number.
  size_t start = 0;  // where the last number read starts, for errors about its value
  auto number = [&](const char* what, long* out) {
    skipSpace();
    start = pos;
    long v = 0;
    while (pos < bytes.size() && std::isdigit(bytes[pos])) {
      if (pos - start == 9) return fail(start, std::string(what) + " has more than 9 digits");
      v = v * 10 + (bytes[pos++] - '0');
    }
    if (pos == start)
      return fail(start, std::string("expected the ") + what + " (a decimal number)" +
                             (pos < bytes.size() ? "" : " but the file ends"));
    if (pos < bytes.size() && !std::isspace(bytes[pos]) && bytes[pos] != '#')
      return fail(pos, std::string(what) + " is not followed by white space");
    *out = v;
    return true;
  };
  const bool plain = bytes.size() >= 2 && bytes[0] == 'P' && bytes[1] == '2';
  if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != '5' && !plain))
    return fail(0, "not a PGM file (it must start with P5 or P2)");
  if (pos < bytes.size() && !std::isspace(bytes[pos]) && bytes[pos] != '#')
    return fail(pos, "the magic number is not followed by white space");
  long w, h, maxval;
  if (!number("width", &w) || !number("height", &h) || !number("maxval", &maxval)) return false;
  if (w < 1 || h < 1) return fail(pos, "width and height must be at least 1");
  if (maxval < 1 || maxval > 65535) return fail(pos, "maxval must be 1 to 65535");
  if (pos >= bytes.size() && !plain) return fail(pos, "the file ends after maxval");
  in->header.num_dims = 2;
  in->header.size_x = static_cast<uint32_t>(w);
  in->header.size_y = static_cast<uint32_t>(h);
  in->header.sample_type = maxval < 256 ? SampleType::kUint8 : SampleType::kUint16;
  if (std::string problem = gridHeaderProblem(in->header); !problem.empty())
    return fail(pos, problem);
  const size_t sample_size = maxval < 256 ? 1 : 2;
  const uint64_t count = uint64_t{in->header.size_x} * in->header.size_y;
  if (plain) {
    // Each value needs at least two bytes with its separator: a size check
    // first keeps a lying header from making a huge buffer.
    if (count > bytes.size()) return fail(pos, "the file is too short for " + std::to_string(w) + "x" +
                                                   std::to_string(h) + " samples");
    in->samples.reserve(count * sample_size);
    for (uint64_t i = 0; i < count; ++i) {
      long v;
      if (!number("next sample", &v)) return false;
      if (v > maxval)
        return fail(start, "sample " + std::to_string(v) + " is above maxval " + std::to_string(maxval));
      in->samples.push_back(static_cast<uint8_t>(v));
      if (sample_size == 2) in->samples.push_back(static_cast<uint8_t>(v >> 8));
    }
    skipSpace();
    if (pos < bytes.size())
      return fail(pos, "data after the " + std::to_string(w) + "x" + std::to_string(h) + " samples");
    return true;
  }
  // Binary samples start after exactly one white-space byte (a comment there
  // would be read as samples by other readers).
  if (!std::isspace(bytes[pos])) return fail(pos, "maxval is not followed by one white-space byte");
  ++pos;
  in->samples.assign(bytes.begin() + static_cast<long>(pos), bytes.end());
  if (sample_size == 2) swapSampleBytes(&in->samples, 2);
  // Netpbm: no sample may exceed maxval (checked over the samples the size
  // check will accept, so a long file gets the size error, not this one).
  for (size_t i = 0; i + sample_size <= in->samples.size() && i < count * sample_size; i += sample_size) {
    long v = in->samples[i] | (sample_size == 2 ? in->samples[i + 1] << 8 : 0);
    if (v > maxval)
      return fail(pos + i, "sample " + std::to_string(v) + " is above maxval " + std::to_string(maxval));
  }
  return true;
}

bool readHgt(const std::string& path, const std::vector<uint8_t>& bytes, GridInput* in,
             std::string* error) {
  // SRTM .hgt: a square of big-endian int16, 1201^2 (3") or 3601^2 (1"), voids -32768.
  size_t n = bytes.size() / 2;
  uint32_t side = static_cast<uint32_t>(std::llround(std::sqrt(static_cast<double>(n))));
  if (bytes.size() % 2 != 0 || uint64_t{side} * side != n || side < 2) {
    *error = path + ": file size " + std::to_string(bytes.size()) +
             " bytes is not a square of at least 2x2 int16 samples (SRTM tiles are 1201x1201 or 3601x3601)";
    return false;
  }
  in->header.num_dims = 2;
  in->header.size_x = in->header.size_y = side;
  in->header.sample_type = SampleType::kInt16;
  in->header.grid_flags = kGridFlagHasNodata;
  in->header.nodata_bits = 0x8000;
  in->samples = bytes;
  swapSampleBytes(&in->samples, 2);
  in->metadata.set("value_units", "m");
  in->metadata.set("crs", "EPSG:4326");
  return true;
}

}  // namespace

bool gridFormatsHaveGdal() { return gdalAvailable(); }

GridFormat gridFormatOf(const std::string& path) {
  if (endsWith(path, ".nrrd")) return GridFormat::kNrrd;
  if (endsWith(path, ".pgm")) return GridFormat::kPgm;
  if (endsWith(path, ".hgt")) return GridFormat::kHgt;
  if (endsWith(path, ".tif") || endsWith(path, ".tiff")) return GridFormat::kGeoTiff;
  return GridFormat::kRaw;
}

bool readGridInput(const std::string& path, const RawLayout& raw, GridInput* in,
                   std::string* error) {
  *in = GridInput{};
  const GridFormat format = gridFormatOf(path);
  // GDAL opens the file itself (a raster may have side files: .aux.xml,
  // world files, a VRT's sources), so only its readability is checked here,
  // for the same error as the other formats.
  if (format == GridFormat::kGeoTiff || (format == GridFormat::kRaw && !raw.has_layout && gdalAvailable())) {
    if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
      std::fclose(f);
    } else {
      *error = path + ": " + std::strerror(errno);
      return false;
    }
    if (!readGdalGrid(path, raw.band, in, error)) {
      if (format == GridFormat::kRaw && error->find(": not a raster GDAL reads") != std::string::npos)
        *error += "; headerless raw input needs --dims and --type";
      return false;
    }
    return true;
  }
  if (raw.band != 0) {
    *error = path + ": --band is for rasters read through GDAL";
    return false;
  }
  std::vector<uint8_t> bytes;
  if (!readWholeFile(path, &bytes, error)) {
    *error = path + ": " + *error;
    return false;
  }
  return readGridBytes(path, format, raw, std::move(bytes), in, error);
}

bool readGridBytes(const std::string& name, GridFormat format, const RawLayout& raw,
                   std::vector<uint8_t> bytes, GridInput* in, std::string* error) {
  *in = GridInput{};
  bool ok;
  switch (format) {
    case GridFormat::kNrrd: ok = readNrrd(name, bytes, in, error); break;
    case GridFormat::kPgm: ok = readPgm(name, bytes, in, error); break;
    case GridFormat::kHgt: ok = readHgt(name, bytes, in, error); break;
    case GridFormat::kGeoTiff:
      // GDAL reads files, with their side files, not bytes (readGridInput).
      *error = name + ": a GeoTIFF is read through GDAL from its file";
      return false;
    default:
      if (!raw.has_layout) {
        *error = name + ": headerless raw input needs --dims and --type";
        return false;
      }
      in->header = raw.header;
      in->samples = std::move(bytes);
      if (raw.big_endian) swapSampleBytes(&in->samples, sampleSize(in->header.sample_type));
      ok = true;
  }
  if (!ok) return false;
  if (std::string problem = gridHeaderProblem(in->header); !problem.empty()) {
    *error = name + ": " + problem;
    return false;
  }
  uint64_t expected = in->header.sampleCount() * sampleSize(in->header.sample_type);
  if (in->samples.size() != expected) {
    *error = name + ": file has " + std::to_string(in->samples.size()) + " bytes of samples but " +
             std::to_string(in->header.size_x) + "x" + std::to_string(in->header.size_y) + "x" +
             std::to_string(in->header.size_z) + " " + sampleTypeName(in->header.sample_type) +
             " needs " + std::to_string(expected);
    return false;
  }
  return true;
}

bool encodeGridOutput(const std::string& path, const GridHeader& header,
                      const Metadata& metadata, const uint32_t size[3],
                      std::vector<uint8_t> samples, bool big_endian,
                      std::vector<uint8_t>* out, std::string* error) {
  std::vector<uint8_t>& body = samples;
  GridFormat format = gridFormatOf(path);
  const size_t bytes = sampleSize(header.sample_type);
  if (format == GridFormat::kGeoTiff) {
    if (big_endian) {
      *error = path + ": --endian is for raw and NRRD output; a GeoTIFF records its own byte order";
      return false;
    }
    return encodeGeoTiff(path, header, metadata, size, body, out, error);
  }
  if (format == GridFormat::kPgm) {
    if (header.num_dims != 2 ||
        (header.sample_type != SampleType::kUint8 && header.sample_type != SampleType::kUint16)) {
      *error = path + ": PGM holds 2-D uint8 or uint16 grids only; write .raw, .nrrd or .tif";
      return false;
    }
    std::string head = "P5\n" + std::to_string(size[0]) + " " + std::to_string(size[1]) + "\n" +
                       (bytes == 1 ? "255" : "65535") + "\n";
    if (bytes == 2) swapSampleBytes(&body, 2);
    out->assign(head.begin(), head.end());
  } else if (format == GridFormat::kNrrd) {
    std::string head = "NRRD0004\n# written by mrsv\ntype: " + std::string(nrrdTypeName(header.sample_type)) +
                       "\ndimension: " + std::to_string(header.num_dims) + "\nsizes:";
    for (int a = 0; a < header.num_dims; ++a) head += " " + std::to_string(size[a]);
    head += std::string("\nendian: ") + (big_endian ? "big" : "little") + "\nencoding: raw\n\n";
    if (big_endian) swapSampleBytes(&body, bytes);
    out->assign(head.begin(), head.end());
  } else if (format == GridFormat::kHgt) {
    *error = path + ": writing .hgt is not supported; write .raw, .nrrd, .pgm or .tif";
    return false;
  } else {  // raw: the samples alone
    if (big_endian) swapSampleBytes(&body, bytes);
    *out = std::move(body);
    return true;
  }
  out->insert(out->end(), body.begin(), body.end());
  return true;
}

Metadata reducedResolutionMetadata(const Metadata& metadata, const GridHeader& header,
                                   const uint8_t levels[3], int reduce_levels) {
  Metadata out = metadata;
  const std::string* text = metadata.find("spacing");
  std::vector<double> spacing;
  if (!text || reduce_levels <= 0 || header.coding == GridCoding::kStored ||
      !parseMetaNumberList(*text, &spacing))
    return out;
  for (size_t a = 0; a < spacing.size() && a < 3; ++a)
    spacing[a] = std::ldexp(spacing[a], std::min(reduce_levels, static_cast<int>(levels[a])));
  out.set("spacing", formatMetaNumberList(spacing));
  return out;
}

namespace {
// Levels to reduce by on every axis: the lattice of every 2^K-th sample.
const uint8_t kEveryAxis[3] = {16, 16, 16};
}  // namespace

Metadata decodedGridMetadata(const DecodedGrid& grid, int reduce_levels) {
  return reducedResolutionMetadata(grid.metadata, grid.header,
                                   grid.header.coding == GridCoding::kTiled ? kEveryAxis : grid.wavelet.levels,
                                   reduce_levels);
}

Metadata decodedRegionMetadata(const DecodedGrid& grid, const uint32_t lo[3], int reduce_levels) {
  uint32_t first[3];
  const uint32_t step = 1u << reduce_levels;
  for (int a = 0; a < 3; ++a) first[a] = (lo[a] + step - 1) / step * step;
  return reducedResolutionMetadata(regionMetadata(grid.metadata, first), grid.header, kEveryAxis, reduce_levels);
}

Metadata regionMetadata(const Metadata& metadata, const uint32_t first[3]) {
  Metadata out = metadata;
  const std::string* origin_text = metadata.find("origin");
  const std::string* spacing_text = metadata.find("spacing");
  std::vector<double> origin, spacing;
  if (!origin_text || !parseMetaNumberList(*origin_text, &origin)) return out;
  if (spacing_text && !parseMetaNumberList(*spacing_text, &spacing)) spacing.clear();
  for (size_t a = 0; a < origin.size() && a < 3; ++a)
    origin[a] += first[a] * (a < spacing.size() ? spacing[a] : 1.0);
  out.set("origin", formatMetaNumberList(origin));
  return out;
}

}  // namespace mrsv
