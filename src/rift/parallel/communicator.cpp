#include "rift/parallel/communicator.hpp"

#include <mpi.h>

#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace rift::parallel {

namespace {

bool started = false;

/// Whether an MPI launcher started this process (Open MPI's mpirun, PMI/PMIx launchers as srun).
bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

}  // namespace

MpiSession::MpiSession(int& argc, char**& argv) {
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  started = true;
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  Communicator::mutable_world() = Communicator(rank, size);
}

MpiSession::~MpiSession() {
  if (started) MPI_Finalize();
  started = false;
}

void MpiSession::abort(int status) {
  if (started) MPI_Abort(MPI_COMM_WORLD, status);
  std::exit(status);
}

Communicator& Communicator::mutable_world() {
  static Communicator w(0, 1);
  return w;
}

const Communicator& Communicator::world() { return mutable_world(); }

void Communicator::sum(double* values, std::size_t count) const {
  if (started && size_ > 1) MPI_Allreduce(MPI_IN_PLACE, values, static_cast<int>(count), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
}

void Communicator::max(double* values, std::size_t count) const {
  if (started && size_ > 1) MPI_Allreduce(MPI_IN_PLACE, values, static_cast<int>(count), MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
}

void Communicator::gather_bytes_into(const void* local, std::size_t bytes, void* (*place)(void*, std::size_t), void* context) const {
  // MPI counts are int: a rank's share up to 2 GiB per call
  const long long mine = static_cast<long long>(bytes);
  std::vector<long long> counts(root() ? static_cast<std::size_t>(size_) : 0);
  MPI_Gather(&mine, 1, MPI_LONG_LONG, counts.data(), 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  std::vector<int> sizes, displacements;
  void* all = nullptr;
  if (root()) {
    long long total = 0;
    for (auto c : counts) {
      if (c > std::numeric_limits<int>::max() || total > std::numeric_limits<int>::max() - c)
        throw std::runtime_error("a gather to rank 0 of more than 2 GiB (use more ranks)");
      sizes.push_back(static_cast<int>(c)), displacements.push_back(static_cast<int>(total)), total += c;
    }
    all = place(context, static_cast<std::size_t>(total));
  }
  MPI_Gatherv(local, static_cast<int>(mine), MPI_BYTE, all, sizes.data(), displacements.data(), MPI_BYTE, 0, MPI_COMM_WORLD);
}

void Communicator::all_gather_bytes_into(const void* local, std::size_t bytes, void* (*place)(void*, std::size_t), void* context) const {
  const long long mine = static_cast<long long>(bytes);
  std::vector<long long> counts(static_cast<std::size_t>(size_));
  MPI_Allgather(&mine, 1, MPI_LONG_LONG, counts.data(), 1, MPI_LONG_LONG, MPI_COMM_WORLD);
  std::vector<int> sizes, displacements;
  long long total = 0;
  for (auto c : counts) {
    if (c > std::numeric_limits<int>::max() || total > std::numeric_limits<int>::max() - c)
      throw std::runtime_error("an all-gather of more than 2 GiB");
    sizes.push_back(static_cast<int>(c)), displacements.push_back(static_cast<int>(total)), total += c;
  }
  void* all = place(context, static_cast<std::size_t>(total));
  MPI_Allgatherv(local, static_cast<int>(mine), MPI_BYTE, all, sizes.data(), displacements.data(), MPI_BYTE, MPI_COMM_WORLD);
}

void Communicator::broadcast(double* values, std::size_t count) const {
  if (started && size_ > 1) MPI_Bcast(values, static_cast<int>(count), MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

void Communicator::barrier() const {
  if (started && size_ > 1) MPI_Barrier(MPI_COMM_WORLD);
}

}  // namespace rift::parallel
