#include "stream_input.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace mrsv::cli {

StreamInput::~StreamInput() {
  if (owned_ && fd_ >= 0) ::close(fd_);
}

bool StreamInput::open(const std::string& path, uint64_t byte_limit, std::string* error) {
  left_ = byte_limit;
  if (path == "-") {
    fd_ = STDIN_FILENO;
    name_ = "standard input";
    return true;
  }
  name_ = path;
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) {
    *error = path + ": " + std::strerror(errno);
    return false;
  }
  owned_ = true;
  return true;
}

bool StreamInput::next(std::vector<uint8_t>* piece, std::string* error) {
  constexpr size_t kPiece = 64 * 1024;
  piece->resize(kPiece);
  if (left_ == 0) {
    // At the limit: one more byte tells whether the input was cut short.
    uint8_t probe;
    ssize_t n;
    do n = ::read(fd_, &probe, 1);
    while (n < 0 && errno == EINTR);
    cut_short_ = n > 0;
    piece->clear();
    return true;
  }
  const size_t want = static_cast<size_t>(std::min<uint64_t>(kPiece, left_));
  ssize_t n;
  do n = ::read(fd_, piece->data(), want);
  while (n < 0 && errno == EINTR);
  if (n < 0) {
    *error = name_ + ": " + std::strerror(errno);
    return false;
  }
  piece->resize(static_cast<size_t>(n));
  left_ -= static_cast<uint64_t>(n);
  return true;
}

}  // namespace mrsv::cli
