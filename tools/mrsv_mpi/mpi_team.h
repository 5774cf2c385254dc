// The MPI ranks of MPI_COMM_WORLD as an EncodeTeam (decision D92): errors
// agreed by reductions, figures summed by MPI_Allreduce, scratch files
// shared through MPI-IO in a directory every rank sees.
#pragma once

#include <mpi.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "mrsv/encode_team.h"

namespace mrsv::mpi {

// One file opened by every rank with MPI-IO. sync() closes it and opens it
// again (collective): MPI-IO's close-barrier-open rule makes every rank's
// writes visible to every rank's reads. (Its other rule, sync-barrier-sync,
// costs an fsync: 0.8 s per level of the mosaic, the whole low-pass part
// written to disk.)
class MpiFile : public SharedScratch {
 public:
  // Collective. `scratch`: removed when closed for good.
  static std::unique_ptr<MpiFile> open(const std::string& path, bool scratch, Error* error);
  ~MpiFile() override;
  Error writeAt(uint64_t offset, const void* data, size_t n) override;
  Error readAt(uint64_t offset, size_t n, void* out) override;
  Error sync() override;
  void close();  // collective

 private:
  MpiFile(MPI_File file, std::string path, bool scratch) : file_(file), path_(std::move(path)), scratch_(scratch) {}
  MPI_File file_;
  std::string path_;
  bool scratch_;
  std::mutex lock_;  // threads of a rank read at once; MPI is initialised for serialized calls
};

class MpiTeam : public EncodeTeam {
 public:
  // Scratch files go to `directory` (shared by every rank).
  explicit MpiTeam(std::string directory);
  int member() const override { return rank_; }
  int members() const override { return ranks_; }
  Error agree(const Error& mine) override;
  void sum(std::vector<uint64_t>* values) override;
  void min(std::vector<double>* values) override;
  void max(std::vector<double>* values) override;
  std::unique_ptr<SharedScratch> scratch(Error* error) override;
  std::unique_ptr<WorkQueue> queue(uint64_t n) override;

 private:
  int rank_ = 0, ranks_ = 1;
  std::string directory_;
  long long job_ = 0;   // rank 0's process id: scratch names of concurrent jobs differ
  int scratches_ = 0;
};

}  // namespace mrsv::mpi
