// The MPI ranks of MPI_COMM_WORLD as an EncodeTeam (decision D92): errors
// agreed by reductions, figures summed by MPI_Allreduce, scratch files
// shared through MPI-IO in a directory every rank sees.
#pragma once

#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

#include "mrsv/encode_team.h"

namespace mrsv::mpi {

// One file opened by every rank with MPI-IO; sync() is the sync-barrier-sync
// that makes every rank's writes visible to every rank's reads (MPI-IO's
// consistency rule for non-atomic mode).
class MpiFile : public SharedScratch {
 public:
  // Collective. `remove_on_close`: a scratch file.
  static std::unique_ptr<MpiFile> open(const std::string& path, bool remove_on_close, Error* error);
  ~MpiFile() override;
  Error writeAt(uint64_t offset, const void* data, size_t n) override;
  Error readAt(uint64_t offset, size_t n, void* out) override;
  Error sync() override;
  void close();  // collective

 private:
  explicit MpiFile(MPI_File file) : file_(file) {}
  MPI_File file_;
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

 private:
  int rank_ = 0, ranks_ = 1;
  std::string directory_;
  long long job_ = 0;   // rank 0's process id: scratch names of concurrent jobs differ
  int scratches_ = 0;
};

}  // namespace mrsv::mpi
