#include "rift/parallel/communicator.hpp"

#include <mpi.h>

#include <cstdlib>

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

std::vector<double> Communicator::gather(const std::vector<double>& local) const {
  if (!started || size_ == 1) return local;
  const int count = static_cast<int>(local.size());
  std::vector<int> counts(root() ? static_cast<std::size_t>(size_) : 0), displacements;
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<double> all;
  if (root()) {
    displacements.assign(counts.size(), 0);
    long total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) displacements[r] = static_cast<int>(total), total += counts[r];
    all.resize(static_cast<std::size_t>(total));
  }
  MPI_Gatherv(local.data(), count, MPI_DOUBLE, all.data(), counts.data(), displacements.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  return all;
}

void Communicator::broadcast(double* values, std::size_t count) const {
  if (started && size_ > 1) MPI_Bcast(values, static_cast<int>(count), MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

void Communicator::barrier() const {
  if (started && size_ > 1) MPI_Barrier(MPI_COMM_WORLD);
}

}  // namespace rift::parallel
