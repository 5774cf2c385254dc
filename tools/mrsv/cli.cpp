#include "cli.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "mrsv/limits.h"

namespace mrsv::cli {
namespace {
bool contains(const std::vector<std::string>& list, const std::string& name) {
  for (const auto& s : list)
    if (s == name) return true;
  return false;
}
}  // namespace

bool Args::parse(int argc, char** argv, const Spec& spec, std::string* error) {
  bool options_done = false;
  for (int i = 0; i < argc; ++i) {
    std::string arg = argv[i];
    if (options_done || arg.size() < 3 || arg.compare(0, 2, "--") != 0) {
      if (arg == "--") {
        options_done = true;
        continue;
      }
      if (!options_done && arg.size() > 1 && arg[0] == '-' && arg != "-") {
        *error = "unknown option '" + arg + "'";
        return false;
      }
      positional_.push_back(arg);
      continue;
    }
    std::string name = arg.substr(2), value;
    bool inline_value = false;
    if (size_t eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      inline_value = true;
    }
    if (contains(spec.flags, name)) {
      if (inline_value) {
        *error = "option '--" + name + "' takes no value";
        return false;
      }
      flags_[name] = true;
    } else if (contains(spec.options, name) || contains(spec.repeatable, name)) {
      if (!inline_value) {
        if (i + 1 >= argc) {
          *error = "option '--" + name + "' needs a value";
          return false;
        }
        value = argv[++i];
      }
      if (values_.count(name) && !contains(spec.repeatable, name)) {
        *error = "option '--" + name + "' given twice";
        return false;
      }
      values_[name].push_back(value);
    } else {
      *error = "unknown option '--" + name + "'";
      return false;
    }
  }
  return true;
}

const std::vector<std::string>& Args::values(const std::string& name) const {
  static const std::vector<std::string> kEmpty;
  auto it = values_.find(name);
  return it == values_.end() ? kEmpty : it->second;
}

int reportError(const char* command, const std::string& file, const Error& error) {
  std::fprintf(stderr, "mrsv %s: %s: %s\n", command, file.c_str(), error.describe().c_str());
  return error.status == Status::kIoError ? kExitIo : kExitInvalidData;
}

int fail(const char* command, const std::string& message, int exit_code) {
  std::fprintf(stderr, "mrsv %s: %s\n", command, message.c_str());
  return exit_code;
}

DecodeOptions levelLimits(const Args& args, const char* cells_option, uint64_t number, const DecodeOptions& options) {
  DecodeOptions limited = options;
  if (args.has(cells_option)) {
    limited.stop_beyond_cells = number;
    if (number == 0) limited.stop_at_vertices = 1;  // the base mesh has more than 0 cells
  } else if (args.has("vertices")) {
    limited.stop_at_vertices = number == 0 ? 1 : number;
  }
  return limited;
}

bool parseUint64(const std::string& text, uint64_t* out) {
  if (text.empty() || text.size() > 19 || text.find_first_not_of("0123456789") != std::string::npos)
    return false;
  *out = std::stoull(text);
  return true;
}

bool parseWholeNumberList(const std::string& text, uint64_t lo, uint64_t hi, std::vector<uint64_t>* out) {
  out->clear();
  for (size_t start = 0; start <= text.size();) {
    const size_t comma = std::min(text.find(',', start), text.size());
    uint64_t v = 0;
    if (!parseUint64(text.substr(start, comma - start), &v) || v < lo || v > hi) return false;
    out->push_back(v);
    start = comma + 1;
  }
  return true;
}

bool parseRegionBox(const std::string& text, GridRegion* region, std::string* error) {
  std::vector<uint64_t> v;
  if (!parseWholeNumberList(text, 0, kMaxGridAxis, &v)) {
    *error = "--region '" + text + "': each coordinate must be a whole number from 0 to " +
             std::to_string(kMaxGridAxis);
    return false;
  }
  if (v.size() != 2 && v.size() != 4 && v.size() != 6) {
    *error = "--region '" + text + "': give X0,X1 or X0,Y0,X1,Y1 or X0,Y0,Z0,X1,Y1,Z1";
    return false;
  }
  const size_t dims = v.size() / 2;
  for (size_t a = 0; a < dims; ++a) {
    region->lo[a] = static_cast<uint32_t>(v[a]);
    region->hi[a] = static_cast<uint32_t>(v[dims + a]);
  }
  return true;
}


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

bool parseDouble(const std::string& text, double* out) {
  char* end = nullptr;
  *out = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size() && std::isfinite(*out);
}

Progress::Progress(const char* label, bool quiet)
    : label_(label), enabled_(!quiet && ::isatty(STDERR_FILENO)) {}

Progress::~Progress() {
  if (enabled_ && last_percent_ >= 0) std::fprintf(stderr, "\r%s: done%24s\n", label_, "");
}

void Progress::update(double fraction) {
  if (!enabled_) return;
  int percent = static_cast<int>(fraction * 100.0);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  std::fprintf(stderr, "\r%s: %3d%%", label_, percent);
  std::fflush(stderr);
}

void Progress::count(uint64_t done, const char* unit) {
  if (!enabled_) return;
  last_percent_ = 0;  // the destructor then prints "done"
  std::fprintf(stderr, "\r%s: %llu %s", label_, static_cast<unsigned long long>(done), unit);
  std::fflush(stderr);
}

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

bool parseMetaOptions(const Args& args, Metadata* metadata, std::string* error) {
  if (!args.has("meta")) return true;
  for (const std::string& entry : args.values("meta")) {
    size_t eq = entry.find('=');
    if (eq == std::string::npos) {
      *error = "--meta '" + entry + "' is not KEY=VALUE";
      return false;
    }
    std::string key = entry.substr(0, eq), value = entry.substr(eq + 1);
    if (std::string problem = metadataEntryProblem(key, value); !problem.empty()) {
      *error = "--meta: " + problem;
      return false;
    }
    if (metadata->find(key)) {
      *error = "--meta: key '" + key + "' given twice";
      return false;
    }
    metadata->entries.emplace_back(key, value);
  }
  return true;
}

}  // namespace mrsv::cli
