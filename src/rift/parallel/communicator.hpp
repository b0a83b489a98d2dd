// The ranks of a distributed run (MPI, as LAMMPS, Peridigm and Uintah use). MPI is started only when
// the process was launched by an MPI launcher (mpirun, srun); a plain `rift run` is a world of one
// rank that makes no MPI call. The header keeps <mpi.h> out of the rest of the code.
#pragma once
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace rift::parallel {

/// Starts MPI for the life of main() where a launcher started this process (MPI_THREAD_FUNNELED:
/// OpenMP teams inside a rank, MPI calls from its main thread only), and finalizes it.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  /// Ends every rank of the run at once with this exit status (an error on one rank while the
  /// others wait in a collective).
  [[noreturn]] static void abort(int status);
};

/// Seconds this process has spent in MPI calls so far (the exchanges, reductions and gathers of
/// Communicator and the halo's refreshes), waiting for the other ranks included: a rank's loop time
/// less these is its own work, which the load-balance report sets beside it.
double seconds_in_mpi();

/// Adds the seconds of its life to seconds_in_mpi() (MPI calls come from the main thread alone).
class MpiClock {
 public:
  MpiClock();
  ~MpiClock();
  MpiClock(const MpiClock&) = delete;
  MpiClock& operator=(const MpiClock&) = delete;

 private:
  double start_;
};

/// MPI_COMM_WORLD, or a world of one rank when MPI was not started.
class Communicator {
 public:
  static const Communicator& world();
  /// This process alone (a rank's local work in a distributed run): no MPI call.
  static const Communicator& one();
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  bool distributed() const { return size_ > 1; }

  /// In place, over every rank: the sums, the maxima.
  void sum(double* values, std::size_t count) const;
  void max(double* values, std::size_t count) const;
  void sum(std::int64_t* values, std::size_t count) const;  // exact (integers)
  double sum(double value) const { sum(&value, 1); return value; }
  double max(double value) const { max(&value, 1); return value; }
  double min(double value) const { value = -value; max(&value, 1); return -value; }
  bool any(bool value) const { return max(value ? 1.0 : 0.0) > 0.0; }
  /// Every rank's `local` one after the other, in rank order, on rank 0 (empty elsewhere).
  template <class T>
  std::vector<T> gather(const std::vector<T>& local) const {
    return gather_to(local, false);
  }
  /// Every rank's `local` one after the other, in rank order, on every rank.
  template <class T>
  std::vector<T> all_gather(const std::vector<T>& local) const {
    return gather_to(local, true);
  }
  /// Point to point: what this rank sends to one other rank, and what it receives from it.
  struct Parcel {
    int peer = 0;
    std::vector<std::byte> send, receive;
  };
  /// Sends each parcel's bytes to its peer and receives the peer's into `receive` (its size comes
  /// first); every peer must name this rank in a parcel of its own. No rank waits on one it does
  /// not exchange with.
  void exchange(std::vector<Parcel>& parcels) const;
  /// Rank 0's values on every rank.
  void broadcast(double* values, std::size_t count) const;
  /// Rank 0's array on every rank (its size too).
  template <class T>
  void broadcast(std::vector<T>& values) const {
    if (!distributed()) return;
    double size = double(values.size());
    broadcast(&size, 1);
    values.resize(static_cast<std::size_t>(size));
    broadcast_bytes(static_cast<void*>(values.data()), values.size() * sizeof(T));
  }
  void barrier() const;

 private:
  /// Every rank's `local` in rank order, on rank 0 or (everyone) on every rank.
  template <class T>
  std::vector<T> gather_to(const std::vector<T>& local, bool everyone) const {
    if (!distributed()) return local;
    std::vector<T> all;
    auto place = [&](std::size_t bytes) {
      all.resize(bytes / sizeof(T));
      return static_cast<void*>(all.data());
    };
    using P = decltype(place);
    gather_bytes(local.data(), local.size() * sizeof(T), everyone, [](void* p, std::size_t total) { return (*static_cast<P*>(p))(total); },
                 &place);
    return all;
  }
  void broadcast_bytes(void* bytes, std::size_t count) const;
  /// The gathers' bytes: place(context, total) gives the receiving rank where they go.
  void gather_bytes(const void* local, std::size_t bytes, bool everyone, void* (*place)(void*, std::size_t), void* context) const;
  Communicator(int rank, int size) : rank_(rank), size_(size) {}
  static Communicator& mutable_world();
  int rank_ = 0, size_ = 1;
  friend class MpiSession;
};

}  // namespace rift::parallel
