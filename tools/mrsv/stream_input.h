// The input of mrsv decode: a file, or standard input for "-", read in pieces
// as they arrive (a pipe hands out what it has), up to an optional byte limit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mrsv::cli {

class StreamInput {
 public:
  StreamInput() = default;
  ~StreamInput();
  StreamInput(const StreamInput&) = delete;
  StreamInput& operator=(const StreamInput&) = delete;

  // `path` "-" is standard input. Stops after `byte_limit` bytes.
  bool open(const std::string& path, uint64_t byte_limit, std::string* error);
  // The next piece (at most 64 KiB, whatever has arrived) in `piece`; an
  // empty piece at the end. False on a read error.
  bool next(std::vector<uint8_t>* piece, std::string* error);
  // The byte limit ended the input before its end (known once next() gave
  // an empty piece).
  bool cutShort() const { return cut_short_; }
  // How messages name the input.
  const std::string& name() const { return name_; }

 private:
  int fd_ = -1;
  bool owned_ = false;
  uint64_t left_ = 0;
  bool cut_short_ = false;
  std::string name_;
};

}  // namespace mrsv::cli
