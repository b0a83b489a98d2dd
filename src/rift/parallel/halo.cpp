#include "rift/parallel/halo.hpp"

#include <mpi.h>

#include <algorithm>

namespace rift::parallel {

Halo::Halo(int rank, const std::vector<std::size_t>& owned, const std::vector<std::size_t>& window_first,
           const std::vector<std::size_t>& window_last) {
  const auto me = static_cast<std::size_t>(rank);
  const std::size_t base = window_first[me];
  for (std::size_t q = 0; q + 1 < owned.size(); ++q) {
    if (q == me) continue;
    // q's particles in my window: my ghosts from q
    const std::size_t from = std::max(window_first[me], owned[q]), to = std::min(window_last[me], owned[q + 1]);
    if (from < to) receive_.push_back({static_cast<int>(q), from - base, to - from});
    // my particles in q's window: q's ghosts from me
    const std::size_t send_from = std::max(window_first[q], owned[me]), send_to = std::min(window_last[q], owned[me + 1]);
    if (send_from < send_to) send_.push_back({static_cast<int>(q), send_from - base, send_to - send_from});
  }
}

void Halo::refresh(double* field, std::size_t width) const {
  MpiClock clock;
  static thread_local std::vector<MPI_Request> requests;  // kept from call to call: no allocation per step
  requests.clear();
  // a message per neighbour and direction: the ranges are contiguous in both windows
  for (const auto& r : receive_)
    MPI_Irecv(field + r.first * width, static_cast<int>(r.count * width), MPI_DOUBLE, r.rank, 0, MPI_COMM_WORLD, &requests.emplace_back());
  for (const auto& s : send_)
    MPI_Isend(field + s.first * width, static_cast<int>(s.count * width), MPI_DOUBLE, s.rank, 0, MPI_COMM_WORLD, &requests.emplace_back());
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

std::size_t Halo::ghosts() const {
  std::size_t n = 0;
  for (const auto& r : receive_) n += r.count;
  return n;
}

std::size_t Halo::sent() const {
  std::size_t n = 0;
  for (const auto& s : send_) n += s.count;
  return n;
}

}  // namespace rift::parallel
