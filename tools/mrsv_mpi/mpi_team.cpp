#include "mpi_team.h"

#include <unistd.h>

#include <algorithm>
#include <climits>

namespace mrsv::mpi {
namespace {

Error ioFailure(const std::string& what) { return Error{Status::kIoError, 0, "file", what}; }

// MPI-IO counts are ints: at most 1 GiB per call.
constexpr uint64_t kMaxCall = uint64_t{1} << 30;

// MPI_Allreduce over a vector in calls of at most INT_MAX elements.
template <typename T>
void allreduce(std::vector<T>* values, MPI_Datatype type, MPI_Op op) {
  for (size_t at = 0; at < values->size(); at += INT_MAX) {
    const int n = static_cast<int>(std::min<size_t>(INT_MAX, values->size() - at));
    MPI_Allreduce(MPI_IN_PLACE, values->data() + at, n, type, op, MPI_COMM_WORLD);
  }
}

// A string from `root` to every rank.
void broadcast(std::string* text, int root) {
  unsigned long long n = text->size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, root, MPI_COMM_WORLD);
  text->resize(n);
  if (n) MPI_Bcast(text->data(), static_cast<int>(n), MPI_CHAR, root, MPI_COMM_WORLD);
}

// The next item is a counter in rank 0's memory, taken with an atomic
// fetch-and-add (MPI one-sided communication, passive target).
class MpiQueue : public WorkQueue {
 public:
  explicit MpiQueue(uint64_t n) : n_(n) {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Win_allocate(rank == 0 ? sizeof(uint64_t) : 0, sizeof(uint64_t), MPI_INFO_NULL, MPI_COMM_WORLD, &next_,
                     &window_);
    if (rank == 0) *next_ = 0;
    MPI_Barrier(MPI_COMM_WORLD);  // the counter is set before anyone takes
    MPI_Win_lock_all(0, window_);
  }
  ~MpiQueue() override {
    MPI_Win_unlock_all(window_);
    MPI_Win_free(&window_);
  }
  uint64_t take() override {
    const uint64_t one = 1;
    uint64_t got = 0;
    MPI_Fetch_and_op(&one, &got, MPI_UINT64_T, 0, 0, MPI_SUM, window_);
    MPI_Win_flush(0, window_);
    return std::min(got, n_);
  }

 private:
  uint64_t n_;
  uint64_t* next_ = nullptr;
  MPI_Win window_ = MPI_WIN_NULL;
};

}  // namespace

std::unique_ptr<MpiFile> MpiFile::open(const std::string& path, bool scratch, Error* error) {
  MPI_File file = MPI_FILE_NULL;
  if (MPI_File_open(MPI_COMM_WORLD, path.c_str(), MPI_MODE_CREATE | MPI_MODE_RDWR, MPI_INFO_NULL, &file) !=
      MPI_SUCCESS) {
    *error = ioFailure(path + ": cannot open with MPI-IO");
    return nullptr;
  }
  *error = {};
  return std::unique_ptr<MpiFile>(new MpiFile(file, path, scratch));
}

MpiFile::~MpiFile() { close(); }

void MpiFile::close() {
  if (file_ == MPI_FILE_NULL) return;
  MPI_File_close(&file_);
  if (!scratch_) return;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) MPI_File_delete(path_.c_str(), MPI_INFO_NULL);
}

Error MpiFile::writeAt(uint64_t offset, const void* data, size_t n) {
  std::lock_guard<std::mutex> hold(lock_);
  const auto* p = static_cast<const uint8_t*>(data);
  while (n > 0) {
    const int part = static_cast<int>(std::min<uint64_t>(n, kMaxCall));
    MPI_Status status;
    if (MPI_File_write_at(file_, static_cast<MPI_Offset>(offset), p, part, MPI_BYTE, &status) != MPI_SUCCESS)
      return ioFailure("an MPI-IO write failed");
    offset += part;
    p += part;
    n -= part;
  }
  return {};
}

Error MpiFile::readAt(uint64_t offset, size_t n, void* out) {
  std::lock_guard<std::mutex> hold(lock_);
  auto* p = static_cast<uint8_t*>(out);
  while (n > 0) {
    const int part = static_cast<int>(std::min<uint64_t>(n, kMaxCall));
    MPI_Status status;
    int got = 0;
    if (MPI_File_read_at(file_, static_cast<MPI_Offset>(offset), p, part, MPI_BYTE, &status) != MPI_SUCCESS ||
        MPI_Get_count(&status, MPI_BYTE, &got) != MPI_SUCCESS || got != part)
      return ioFailure("an MPI-IO read failed");
    offset += part;
    p += part;
    n -= part;
  }
  return {};
}

Error MpiFile::sync() {
  if (file_ != MPI_FILE_NULL) MPI_File_close(&file_);
  MPI_Barrier(MPI_COMM_WORLD);
  return MPI_File_open(MPI_COMM_WORLD, path_.c_str(), MPI_MODE_RDWR, MPI_INFO_NULL, &file_) == MPI_SUCCESS
             ? Error{}
             : ioFailure(path_ + ": cannot open again with MPI-IO");
}

MpiTeam::MpiTeam(std::string directory) : directory_(std::move(directory)) {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
  job_ = static_cast<long long>(getpid());
  MPI_Bcast(&job_, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
}

Error MpiTeam::agree(const Error& mine) {
  int failed = mine.ok() ? ranks_ : rank_, first = ranks_;
  MPI_Allreduce(&failed, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == ranks_) return {};
  Error e = mine;
  int status = static_cast<int>(e.status);
  unsigned long long offset = e.offset;
  MPI_Bcast(&status, 1, MPI_INT, first, MPI_COMM_WORLD);
  MPI_Bcast(&offset, 1, MPI_UNSIGNED_LONG_LONG, first, MPI_COMM_WORLD);
  broadcast(&e.field, first);
  broadcast(&e.message, first);
  e.status = static_cast<Status>(status);
  e.offset = offset;
  return e;
}

void MpiTeam::sum(std::vector<uint64_t>* values) { allreduce(values, MPI_UINT64_T, MPI_SUM); }
void MpiTeam::min(std::vector<double>* values) { allreduce(values, MPI_DOUBLE, MPI_MIN); }
void MpiTeam::max(std::vector<double>* values) { allreduce(values, MPI_DOUBLE, MPI_MAX); }

std::unique_ptr<SharedScratch> MpiTeam::scratch(Error* error) {
  const std::string path =
      directory_ + "/.mrsv-mpi-scratch-" + std::to_string(job_) + "-" + std::to_string(scratches_++);
  return MpiFile::open(path, true, error);
}

std::unique_ptr<WorkQueue> MpiTeam::queue(uint64_t n) { return std::make_unique<MpiQueue>(n); }

}  // namespace mrsv::mpi
