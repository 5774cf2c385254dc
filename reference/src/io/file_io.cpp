#include "mrsv/file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace mrsv {

bool readWholeFile(const std::string& path, std::vector<uint8_t>* out, std::string* error) {
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    *error = std::strerror(errno);
    return false;
  }
  struct stat st;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    *error = S_ISDIR(st.st_mode) ? "is a directory" : "not a regular file";
    ::close(fd);
    return false;
  }
  out->resize(static_cast<size_t>(st.st_size));
  size_t done = 0;
  while (done < out->size()) {
    ssize_t n = ::read(fd, out->data() + done, out->size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      *error = n == 0 ? "file shrank while reading" : std::strerror(errno);
      ::close(fd);
      return false;
    }
    done += static_cast<size_t>(n);
  }
  ::close(fd);
  return true;
}

bool writeFileAtomically(const std::string& path, const std::vector<uint8_t>& bytes,
                         std::string* error) {
  std::string temp = path + ".mrsv-tmp-" + std::to_string(::getpid());
  int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    *error = std::string("cannot create temporary file: ") + std::strerror(errno);
    return false;
  }
  size_t done = 0;
  bool ok = true;
  while (done < bytes.size()) {
    ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      *error = std::strerror(errno);
      ok = false;
      break;
    }
    done += static_cast<size_t>(n);
  }
  if (ok && ::fsync(fd) != 0) {
    *error = std::strerror(errno);
    ok = false;
  }
  if (::close(fd) != 0 && ok) {
    *error = std::strerror(errno);
    ok = false;
  }
  if (ok && ::rename(temp.c_str(), path.c_str()) != 0) {
    *error = std::strerror(errno);
    ok = false;
  }
  if (!ok) ::unlink(temp.c_str());
  return ok;
}

bool isSameFile(const std::string& a, const std::string& b) {
  struct stat sa, sb;
  if (::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return false;
  return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ >= 0) {
    ::close(fd_);
    ::unlink(temp_.c_str());
  }
}

bool AtomicFileWriter::open(const std::string& path, std::string* error) {
  path_ = path;
  temp_ = path + ".mrsv-tmp-" + std::to_string(::getpid());
  fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd_ < 0) *error = std::string("cannot create temporary file: ") + std::strerror(errno);
  return fd_ >= 0;
}

bool AtomicFileWriter::write(const uint8_t* data, size_t size) {
  while (size > 0 && error_.empty()) {
    ssize_t n = ::write(fd_, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error_ = std::strerror(errno);
      break;
    }
    data += n;
    size -= static_cast<size_t>(n);
    written_ += static_cast<uint64_t>(n);
  }
#ifdef __linux__
  // Start the writeback of what has piled up, without waiting for it: the
  // fsync of commit() (64 MiB: 30 ms after a volume's decode) then overlaps
  // the work that produced the data. Only a hint; errors surface at fsync.
  constexpr uint64_t kFlushStep = uint64_t{8} << 20;
  if (error_.empty() && written_ - flushing_from_ >= kFlushStep) {
    ::sync_file_range(fd_, static_cast<off_t>(flushing_from_), static_cast<off_t>(written_ - flushing_from_),
                      SYNC_FILE_RANGE_WRITE);
    flushing_from_ = written_;
  }
#endif
  return error_.empty();
}

bool AtomicFileWriter::commit(std::string* error) {
  if (error_.empty() && ::fsync(fd_) != 0) error_ = std::strerror(errno);
  if (::close(fd_) != 0 && error_.empty()) error_ = std::strerror(errno);
  fd_ = -1;
  if (error_.empty() && ::rename(temp_.c_str(), path_.c_str()) != 0) error_ = std::strerror(errno);
  if (!error_.empty()) {
    ::unlink(temp_.c_str());
    *error = error_;
    return false;
  }
  return true;
}

namespace {
class RawBoxReader : public GridBoxReader {
 public:
  RawBoxReader(int fd, const GridHeader& h, Endian endian) : fd_(fd), h_(h), endian_(endian) {}
  ~RawBoxReader() override { ::close(fd_); }
  bool read(const uint32_t origin[3], const uint32_t size[3], uint8_t* out, std::string* error) override {
    const size_t bytes = sampleSize(h_.sample_type);
    const size_t row = size_t{size[0]} * bytes;
    for (uint32_t z = 0; z < size[2]; ++z)
      for (uint32_t y = 0; y < size[1]; ++y, out += row) {
        const uint64_t at = ((uint64_t{origin[2] + z} * h_.size_y + origin[1] + y) * h_.size_x + origin[0]) * bytes;
        for (size_t done = 0; done < row;) {
          ssize_t n = ::pread(fd_, out + done, row - done, static_cast<off_t>(at + done));
          if (n < 0 && errno == EINTR) continue;
          if (n <= 0) {
            *error = n == 0 ? "the file ended early" : std::strerror(errno);
            return false;
          }
          done += static_cast<size_t>(n);
        }
        if (endian_ == Endian::kBig)
          for (size_t i = 0; i < row; i += bytes) std::reverse(out + i, out + i + bytes);
      }
    return true;
  }

 private:
  int fd_;
  GridHeader h_;
  Endian endian_;
};
}  // namespace

std::unique_ptr<GridBoxReader> openRawBoxReader(const std::string& path, const GridHeader& header, Endian endian,
                                                std::string* error) {
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    *error = path + ": " + std::strerror(errno);
    return nullptr;
  }
  struct stat st;
  const uint64_t expected = header.sampleCount() * sampleSize(header.sample_type);
  if (::fstat(fd, &st) != 0 || static_cast<uint64_t>(st.st_size) != expected) {
    *error = path + ": " + std::to_string(st.st_size) + " bytes, but --dims and --type make " +
             std::to_string(expected);
    ::close(fd);
    return nullptr;
  }
  return std::make_unique<RawBoxReader>(fd, header, endian);
}

}  // namespace mrsv
