// Shared pieces of the mrsv command line: argument parsing, error lines, progress.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "mrsv/grid.h"
#include "mrsv/metadata.h"
#include "mrsv/status.h"
#include "mrsv/tiled_grid.h"

namespace mrsv::cli {

// Exit statuses of every subcommand (documented in README and --help).
constexpr int kExitOk = 0;
constexpr int kExitInvalidData = 1;  // the input breaks a rule of the format or of its layout
constexpr int kExitUsage = 2;        // the command line is wrong
constexpr int kExitIo = 3;           // a file could not be read or written

// A small parser: options take "--name value" or "--name=value"; flags take
// nothing; options listed as repeatable may appear more than once.
class Args {
 public:
  struct Spec {
    std::vector<std::string> options;      // take a value
    std::vector<std::string> flags;        // take none
    std::vector<std::string> repeatable;   // options that may repeat
  };
  // Returns false and sets error on an unknown option or a missing value.
  bool parse(int argc, char** argv, const Spec& spec, std::string* error);

  bool flag(const std::string& name) const { return flags_.count(name) != 0; }
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  const std::string& value(const std::string& name) const { return values_.at(name).front(); }
  const std::vector<std::string>& values(const std::string& name) const;
  const std::vector<std::string>& positional() const { return positional_; }

 private:
  std::map<std::string, std::vector<std::string>> values_;
  std::map<std::string, bool> flags_;
  std::vector<std::string> positional_;
};

// "mrsv CMD: FILE: offset N: E111 name: field: message" on stderr; returns kExitInvalidData.
int reportError(const char* command, const std::string& file, const Error& error);
// "mrsv CMD: message" on stderr; returns `exit_code`.
int fail(const char* command, const std::string& message, int exit_code);

// Parses a whole non-negative decimal number; false when not one.
bool parseUint64(const std::string& text, uint64_t* out);
// A finite number written whole (strtod syntax), e.g. "0.5", "1e-3".
bool parseDouble(const std::string& text, double* out);
// "A[,B[,...]]" of whole numbers, each from lo to hi. False on anything else.
bool parseWholeNumberList(const std::string& text, uint64_t lo, uint64_t hi, std::vector<uint64_t>* out);
// "X0,Y0[,Z0],X1,Y1[,Z1]" (--region): a half-open box of samples; false with
// `error` naming the rule when it is not one.
bool parseRegionBox(const std::string& text, GridRegion* region, std::string* error);
// The --nodata text as the bit pattern of a sample of `type` (spec 3.1
// nodata_bits); false with `error` set when it is not a value of that type.
bool parseNodata(const std::string& text, SampleType type, uint64_t* bits, std::string* error);

// `options` with the stop of a progressive mesh decode at the level asked for
// (DecodeOptions::stop_*): --<cells_option> N decodes up to the first batch past
// N triangles or tets, --vertices N up to N vertices, 0 of either the base mesh
// alone; --fraction needs the finest count and decodes everything. `number` is
// the option's parsed value.
DecodeOptions levelLimits(const Args& args, const char* cells_option, uint64_t number, const DecodeOptions& options);

// `s` as a JSON string literal, quotes included.
std::string jsonString(const std::string& s);

// The repeatable --meta KEY=VALUE options into `metadata` (spec 2.6 rules);
// false with one line in `error` on a malformed or repeated entry.
bool parseMetaOptions(const Args& args, Metadata* metadata, std::string* error);

// Progress on stderr, only when it is a terminal and not --quiet.
class Progress {
 public:
  Progress(const char* label, bool quiet);
  ~Progress();
  void update(double fraction);
  // For work whose total is not known in advance: a count that grows.
  void count(uint64_t done, const char* unit);

 private:
  const char* label_;
  bool enabled_;
  int last_percent_ = -1;
};

}  // namespace mrsv::cli
