// Grid file formats of the tools: headerless raw, NRRD (attached, raw
// encoding), binary PGM (P5, 8 or 16 bit), SRTM .hgt, and rasters through
// GDAL (gdal_grid.cpp) in builds that have it.
#include "mrsv/grid_formats.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <utility>

#include "io/gdal_grid.h"
#include "io/number_list.h"
#include "mrsv/file_io.h"
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

// "(1,0,0) (0,1,0)" or "1 1 2" → "1,1,2" for the meta chunk; empty if unusable.
std::string numberList(const std::string& text) {
  std::string out;
  std::string token;
  std::istringstream in(text);
  while (in >> token) {
    token.erase(std::remove_if(token.begin(), token.end(),
                               [](char c) { return c == '(' || c == ')'; }),
                token.end());
    if (token.empty() || token == "none" || token == "nan") return {};
    out += (out.empty() ? "" : ",") + token;
  }
  return out;
}

bool readNrrd(const std::string& path, const std::vector<uint8_t>& bytes, GridInput* in,
              std::string* error) {
  size_t pos = 0;
  auto line = [&](std::string* out) {
    if (pos >= bytes.size()) return false;
    size_t end = pos;
    while (end < bytes.size() && bytes[end] != '\n') ++end;
    *out = std::string(reinterpret_cast<const char*>(bytes.data() + pos), end - pos);
    if (!out->empty() && out->back() == '\r') out->pop_back();
    pos = end + 1;
    return true;
  };
  std::string text;
  if (!line(&text) || text.compare(0, 4, "NRRD") != 0) {
    *error = path + ": not an NRRD file (no NRRD magic line)";
    return false;
  }
  std::string type, encoding = "raw", endian = "little", sizes, spacings, origin;
  int dimension = 0;
  while (line(&text) && !text.empty()) {
    if (text[0] == '#') continue;
    size_t colon = text.find(':');
    if (colon == std::string::npos) continue;
    std::string key = lower(trim(text.substr(0, colon)));
    std::string value = trim(text.substr(colon + 1));
    if (!value.empty() && value[0] == '=') continue;  // key:=value pairs
    if (key == "type") type = lower(value);
    else if (key == "dimension") dimension = std::atoi(value.c_str());
    else if (key == "sizes") sizes = value;
    else if (key == "encoding") encoding = lower(value);
    else if (key == "endian") endian = lower(value);
    else if (key == "spacings") spacings = value;
    else if (key == "space origin") origin = value;
    else if (key == "data file" || key == "datafile") {
      *error = path + ": detached NRRD headers are not supported; attach the data (unu save)";
      return false;
    }
  }
  if (!nrrdType(type, &in->header.sample_type)) {
    *error = path + ": NRRD type '" + type + "' is not one of uint8, int16, uint16, int32, float, double";
    return false;
  }
  if (encoding != "raw") {
    *error = path + ": NRRD encoding '" + encoding + "' is not supported (only raw)";
    return false;
  }
  if (dimension < 1 || dimension > 3) {
    *error = path + ": NRRD dimension " + std::to_string(dimension) + " (MRSV grids have 1 to 3)";
    return false;
  }
  std::string dims = numberList(sizes);
  if (std::string problem = parseDims(dims, &in->header); !problem.empty() ||
                                                          in->header.num_dims != dimension) {
    *error = path + ": NRRD sizes '" + sizes + "' do not match dimension " + std::to_string(dimension);
    return false;
  }
  in->samples.assign(bytes.begin() + static_cast<long>(std::min(pos, bytes.size())), bytes.end());
  if (endian == "big") swapSampleBytes(&in->samples, sampleSize(in->header.sample_type));
  if (std::string s = numberList(spacings); !s.empty()) in->metadata.set("spacing", s);
  if (std::string s = numberList(origin); !s.empty()) in->metadata.set("origin", s);
  return true;
}

bool readPgm(const std::string& path, const std::vector<uint8_t>& bytes, GridInput* in,
             std::string* error) {
  // P5 header: magic, width, height, maxval, separated by white space and comments.
  size_t pos = 2;
  auto number = [&](long* out) {
    while (pos < bytes.size()) {
      if (bytes[pos] == '#') {
        while (pos < bytes.size() && bytes[pos] != '\n') ++pos;
      } else if (std::isspace(bytes[pos])) {
        ++pos;
      } else {
        break;
      }
    }
    long v = 0;
    size_t start = pos;
    while (pos < bytes.size() && std::isdigit(bytes[pos]) && pos - start < 9) v = v * 10 + (bytes[pos++] - '0');
    *out = v;
    return pos > start;
  };
  long w, h, maxval;
  if (bytes.size() < 2 || bytes[0] != 'P' || bytes[1] != '5' || !number(&w) || !number(&h) ||
      !number(&maxval) || pos >= bytes.size() || !std::isspace(bytes[pos])) {
    *error = path + ": not a binary PGM (P5) file";
    return false;
  }
  ++pos;
  if (w < 1 || h < 1 || maxval < 1 || maxval > 65535) {
    *error = path + ": PGM width, height or maxval out of range";
    return false;
  }
  in->header.num_dims = 2;
  in->header.size_x = static_cast<uint32_t>(w);
  in->header.size_y = static_cast<uint32_t>(h);
  in->header.sample_type = maxval < 256 ? SampleType::kUint8 : SampleType::kUint16;
  in->samples.assign(bytes.begin() + static_cast<long>(pos), bytes.end());
  // Netpbm stores 16-bit samples most significant byte first.
  if (in->header.sample_type == SampleType::kUint16) swapSampleBytes(&in->samples, 2);
  return true;
}

bool readHgt(const std::string& path, const std::vector<uint8_t>& bytes, GridInput* in,
             std::string* error) {
  // SRTM .hgt: a square of big-endian int16, 1201^2 (3") or 3601^2 (1"), voids -32768.
  size_t n = bytes.size() / 2;
  uint32_t side = static_cast<uint32_t>(std::llround(std::sqrt(static_cast<double>(n))));
  if (bytes.size() % 2 != 0 || uint64_t{side} * side != n || side < 2) {
    *error = path + ": .hgt size " + std::to_string(bytes.size()) +
             " bytes is not a square of int16 samples (1201x1201 or 3601x3601)";
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
  GridFormat format = gridFormatOf(path);
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
  bool ok;
  switch (format) {
    case GridFormat::kNrrd: ok = readNrrd(path, bytes, in, error); break;
    case GridFormat::kPgm: ok = readPgm(path, bytes, in, error); break;
    case GridFormat::kHgt: ok = readHgt(path, bytes, in, error); break;
    default:
      if (!raw.has_layout) {
        *error = path + ": headerless raw input needs --dims and --type";
        return false;
      }
      in->header = raw.header;
      in->samples = std::move(bytes);
      if (raw.big_endian) swapSampleBytes(&in->samples, sampleSize(in->header.sample_type));
      ok = true;
  }
  if (!ok) return false;
  if (std::string problem = gridHeaderProblem(in->header); !problem.empty()) {
    *error = path + ": " + problem;
    return false;
  }
  uint64_t expected = in->header.sampleCount() * sampleSize(in->header.sample_type);
  if (in->samples.size() != expected) {
    *error = path + ": file has " + std::to_string(in->samples.size()) + " bytes of samples but " +
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
  if (!text || reduce_levels <= 0 || header.coding != GridCoding::kWavelet ||
      !parseMetaNumberList(*text, &spacing))
    return out;
  for (size_t a = 0; a < spacing.size() && a < 3; ++a)
    spacing[a] = std::ldexp(spacing[a], std::min(reduce_levels, static_cast<int>(levels[a])));
  out.set("spacing", formatMetaNumberList(spacing));
  return out;
}

}  // namespace mrsv
