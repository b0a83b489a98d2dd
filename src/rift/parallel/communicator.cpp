#include "rift/parallel/communicator.hpp"

#include <chrono>

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

namespace {
double mpi_seconds = 0.0;
double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
}  // namespace

double seconds_in_mpi() { return mpi_seconds; }
MpiClock::MpiClock() : start_(now()) {}
MpiClock::~MpiClock() { mpi_seconds += now() - start_; }

const Communicator& Communicator::world() { return mutable_world(); }

const Communicator& Communicator::one() {
  static const Communicator alone(0, 1);
  return alone;
}

void Communicator::sum(double* values, std::size_t count) const {
  if (!started || size_ < 2) return;
  MpiClock clock;
  MPI_Allreduce(MPI_IN_PLACE, values, static_cast<int>(count), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
}

void Communicator::sum(std::int64_t* values, std::size_t count) const {
  if (!started || size_ < 2) return;
  MpiClock clock;
  MPI_Allreduce(MPI_IN_PLACE, values, static_cast<int>(count), MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
}

void Communicator::max(double* values, std::size_t count) const {
  if (!started || size_ < 2) return;
  MpiClock clock;
  MPI_Allreduce(MPI_IN_PLACE, values, static_cast<int>(count), MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
}

void Communicator::gather_bytes(const void* local, std::size_t bytes, bool everyone, void* (*place)(void*, std::size_t),
                                void* context) const {
  MpiClock clock;
  // MPI counts are int: up to 2 GiB per call
  const long long mine = static_cast<long long>(bytes);
  std::vector<long long> counts(everyone || root() ? static_cast<std::size_t>(size_) : 0);
  if (everyone) MPI_Allgather(&mine, 1, MPI_LONG_LONG, counts.data(), 1, MPI_LONG_LONG, MPI_COMM_WORLD);
  else MPI_Gather(&mine, 1, MPI_LONG_LONG, counts.data(), 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  std::vector<int> sizes, displacements;
  void* all = nullptr;
  if (!counts.empty()) {
    long long total = 0;
    for (auto c : counts) {
      if (c > std::numeric_limits<int>::max() || total > std::numeric_limits<int>::max() - c)
        throw std::runtime_error("a gather of more than 2 GiB (use more ranks)");
      sizes.push_back(static_cast<int>(c)), displacements.push_back(static_cast<int>(total)), total += c;
    }
    all = place(context, static_cast<std::size_t>(total));
  }
  if (everyone)
    MPI_Allgatherv(local, static_cast<int>(mine), MPI_BYTE, all, sizes.data(), displacements.data(), MPI_BYTE, MPI_COMM_WORLD);
  else
    MPI_Gatherv(local, static_cast<int>(mine), MPI_BYTE, all, sizes.data(), displacements.data(), MPI_BYTE, 0, MPI_COMM_WORLD);
}

void Communicator::exchange(std::vector<Parcel>& parcels) const {
  if (!started || size_ < 2) return;
  MpiClock clock;
  std::vector<MPI_Request> requests;
  requests.reserve(2 * parcels.size());
  std::vector<long long> sizes(parcels.size()), theirs(parcels.size());
  for (std::size_t k = 0; k < parcels.size(); ++k) {
    sizes[k] = static_cast<long long>(parcels[k].send.size());
    MPI_Irecv(&theirs[k], 1, MPI_LONG_LONG, parcels[k].peer, 1, MPI_COMM_WORLD, &requests.emplace_back());
    MPI_Isend(&sizes[k], 1, MPI_LONG_LONG, parcels[k].peer, 1, MPI_COMM_WORLD, &requests.emplace_back());
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  requests.clear();
  for (std::size_t k = 0; k < parcels.size(); ++k) {
    if (theirs[k] > std::numeric_limits<int>::max() || sizes[k] > std::numeric_limits<int>::max())
      throw std::runtime_error("a message of more than 2 GiB between two ranks (use more ranks)");
    parcels[k].receive.resize(static_cast<std::size_t>(theirs[k]));
    MPI_Irecv(parcels[k].receive.data(), static_cast<int>(theirs[k]), MPI_BYTE, parcels[k].peer, 2, MPI_COMM_WORLD, &requests.emplace_back());
    MPI_Isend(parcels[k].send.data(), static_cast<int>(sizes[k]), MPI_BYTE, parcels[k].peer, 2, MPI_COMM_WORLD, &requests.emplace_back());
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

void Communicator::broadcast(double* values, std::size_t count) const {
  if (!started || size_ < 2) return;
  MpiClock clock;
  MPI_Bcast(values, static_cast<int>(count), MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

void Communicator::broadcast_bytes(void* bytes, std::size_t count) const {
  if (count > static_cast<std::size_t>(std::numeric_limits<int>::max())) throw std::runtime_error("a broadcast of more than 2 GiB");
  if (!started || size_ < 2) return;
  MpiClock clock;
  MPI_Bcast(bytes, static_cast<int>(count), MPI_BYTE, 0, MPI_COMM_WORLD);
}

void Communicator::barrier() const {
  if (!started || size_ < 2) return;
  MpiClock clock;
  MPI_Barrier(MPI_COMM_WORLD);
}

}  // namespace rift::parallel
