#include "rift/pd/halo.hpp"

#include <mpi.h>

#include <algorithm>

#include "rift/parallel/communicator.hpp"

namespace rift::pd {

namespace {

/// The common part of two lists of ranges (each ascending and apart), ascending.
std::vector<IndexRange> common(const std::vector<IndexRange>& a, const std::vector<IndexRange>& b) {
  std::vector<IndexRange> out;
  for (std::size_t p = 0, q = 0; p < a.size() && q < b.size();) {
    const std::size_t first = std::max(a[p].first, b[q].first), last = std::min(a[p].last, b[q].last);
    if (first < last) out.push_back({first, last});
    if (a[p].last < b[q].last) ++p;
    else ++q;
  }
  return out;
}

}  // namespace

Halo::Halo(int rank, const std::vector<std::vector<IndexRange>>& owned, const std::vector<std::vector<IndexRange>>& windows,
           const Numbering& here) {
  const auto me = static_cast<std::size_t>(rank);
  for (std::size_t q = 0; q < owned.size(); ++q) {
    if (q == me) continue;
    // q's particles in my window: my ghosts from q; my particles in q's window: q's ghosts from me.
    // Both ranks list them in the whole run's order, so the messages' entries match.
    if (auto from_q = here.here_of(common(windows[me], owned[q])); !from_q.empty()) receive_.push_back({static_cast<int>(q), std::move(from_q)});
    if (auto to_q = here.here_of(common(windows[q], owned[me])); !to_q.empty()) send_.push_back({static_cast<int>(q), std::move(to_q)});
  }
}

void Halo::refresh(double* field, std::size_t width) const {
  parallel::MpiClock clock;
  static thread_local std::vector<MPI_Request> requests;  // kept from call to call: no allocation per step
  static thread_local std::vector<std::vector<double>> packed;  // a peer's entries where they are several ranges
  requests.clear();
  packed.resize(receive_.size() + send_.size());
  auto count_of_entries = [&](const Peer& p) {
    std::size_t n = 0;
    for (const IndexRange& r : p.ranges) n += r.size() * width;
    return n;
  };
  // one range: straight from and into the field; several: through a buffer
  for (std::size_t k = 0; k < receive_.size(); ++k) {
    const Peer& r = receive_[k];
    double* into = field + r.ranges[0].first * width;
    if (r.ranges.size() > 1) packed[k].resize(count_of_entries(r)), into = packed[k].data();
    MPI_Irecv(into, static_cast<int>(count_of_entries(r)), MPI_DOUBLE, r.rank, 0, MPI_COMM_WORLD, &requests.emplace_back());
  }
  for (std::size_t k = 0; k < send_.size(); ++k) {
    const Peer& s = send_[k];
    const double* from = field + s.ranges[0].first * width;
    if (s.ranges.size() > 1) {
      auto& buffer = packed[receive_.size() + k];
      buffer.clear();
      for (const IndexRange& a : s.ranges) buffer.insert(buffer.end(), field + a.first * width, field + a.last * width);
      from = buffer.data();
    }
    MPI_Isend(from, static_cast<int>(count_of_entries(s)), MPI_DOUBLE, s.rank, 0, MPI_COMM_WORLD, &requests.emplace_back());
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  for (std::size_t k = 0; k < receive_.size(); ++k) {
    const Peer& r = receive_[k];
    if (r.ranges.size() < 2) continue;
    const double* from = packed[k].data();
    for (const IndexRange& a : r.ranges) {
      std::copy(from, from + a.size() * width, field + a.first * width);
      from += a.size() * width;
    }
  }
}

std::size_t Halo::ghosts() const {
  std::size_t n = 0;
  for (const auto& r : receive_) n += count_of(r.ranges);
  return n;
}

std::size_t Halo::sent() const {
  std::size_t n = 0;
  for (const auto& s : send_) n += count_of(s.ranges);
  return n;
}

}  // namespace rift::pd
