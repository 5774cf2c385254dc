// Whole-file I/O for the tools: never a half-written output, never the input overwritten.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mrsv {

// Reads all of `path`. On failure returns false and sets `error` to one line.
bool readWholeFile(const std::string& path, std::vector<uint8_t>* out, std::string* error);

// Writes `bytes` to a temporary file beside `path`, flushes it and renames it
// over `path`, so readers see either the old file or the whole new one.
bool writeFileAtomically(const std::string& path, const std::vector<uint8_t>& bytes,
                         std::string* error);

// True when both paths name the same existing file (also through links).
bool isSameFile(const std::string& a, const std::string& b);

}  // namespace mrsv
