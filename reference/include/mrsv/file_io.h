// Whole-file I/O for the tools: never a half-written output, never the input overwritten.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mrsv/grid.h"
#include "mrsv/raw_grid.h"
#include "mrsv/tiled_grid.h"

namespace mrsv {

// Reads all of `path`. On failure returns false and sets `error` to one line.
bool readWholeFile(const std::string& path, std::vector<uint8_t>* out, std::string* error);

// Writes `bytes` to a temporary file beside `path`, flushes it and renames it
// over `path`, so readers see either the old file or the whole new one.
bool writeFileAtomically(const std::string& path, const std::vector<uint8_t>& bytes,
                         std::string* error);

// A file written piece by piece under a temporary name beside `path` and
// renamed over it by commit(); without commit() (an error on the way) the
// temporary file is removed, so no half-written output is ever left. The
// disk writes start as the pieces arrive (every 8 MiB), so that commit()'s
// flush waits for the last ones only.
class AtomicFileWriter : public ByteSink {
 public:
  ~AtomicFileWriter() override;
  bool open(const std::string& path, std::string* error);
  bool write(const uint8_t* data, size_t size) override;
  bool commit(std::string* error);

 private:
  std::string path_, temp_, error_;
  int fd_ = -1;
  uint64_t written_ = 0, flushing_from_ = 0;  // bytes written; the first not yet sent to the disk
};

// The samples of a headerless raw grid file (x fastest, then y, then z), read
// a box at a time with pread. Null with `error` set when the file cannot be
// opened or its size is not the grid's.
std::unique_ptr<GridBoxReader> openRawBoxReader(const std::string& path, const GridHeader& header, Endian endian,
                                                std::string* error);

// True when both paths name the same existing file (also through links).
bool isSameFile(const std::string& a, const std::string& b);

}  // namespace mrsv
