// What OpenMP's synchronization costs on this machine, against the passes of an MPM step.
//
//     c++ -O2 -fopenmp bench/team_overhead.cpp -o team_overhead && ./team_overhead [repeats]
//
// region:  fork a team of two and join it, with nothing to do (one per `omp parallel for`);
// barrier: one `omp barrier` inside a standing team of two.
// A 2D MPM step of 9,600 points lasts about 1 ms and has seven regions, so when a thread waits much
// longer than seven regions' worth, it waits on the other thread's work, not on the runtime
// (bench/README.md, session of 2026-11-29, eleventh).
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const int rounds = 20000;
  std::vector<double> region(repeats), barrier(repeats);
  volatile int sink = 0;
  for (int r = 0; r < repeats; ++r) {
    double t0 = omp_get_wtime();
    for (int i = 0; i < rounds; ++i) {
#pragma omp parallel num_threads(2)
      {
        if (omp_get_thread_num() == 0) sink = sink + 1;
      }
    }
    double t1 = omp_get_wtime();
#pragma omp parallel num_threads(2)
    for (int i = 0; i < rounds; ++i) {
#pragma omp barrier
    }
    double t2 = omp_get_wtime();
    region[static_cast<std::size_t>(r)] = (t1 - t0) / rounds * 1e6;
    barrier[static_cast<std::size_t>(r)] = (t2 - t1) / rounds * 1e6;
  }
  std::sort(region.begin(), region.end());
  std::sort(barrier.begin(), barrier.end());
  std::printf("region %.2f us, barrier %.2f us (median of %d, %d rounds each)\n", region[region.size() / 2],
              barrier[barrier.size() / 2], repeats, rounds);
  return 0;
}
