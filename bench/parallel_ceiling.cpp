// The most two threads can gain on this machine: work with nothing shared between the threads.
//
//     c++ -O2 -fopenmp bench/parallel_ceiling.cpp -o ceiling && ./ceiling [repeats]
//
// Each kernel runs a fixed amount of work on one thread, then the same work split in halves on two
// threads, each on its own data (no shared cache lines, no reduction in the loop, one barrier at the
// end). The ratio of the two times is what a perfectly parallel code could reach here; a virtual
// machine whose two CPUs share a core, or whose clock drops when both are busy, gives less than 2.
// bench/run_mpm prints it beside the MPM speed-ups, so that those read against the machine.
//   compute:    four independent chains of multiply-adds on registers (latency-bound: each chain
//               waits on its last result, so it reads the clock and leaves the core's floating-point
//               units mostly idle);
//   throughput: twelve independent chains of two-wide multiply-adds (enough to keep the
//               floating-point units busy: it reads how much of them the thread gets, which a
//               virtual CPU shares with whatever runs on the same physical core);
//   cache:      sweeps of a multiply-add over 256 KiB of private array per thread (L2-resident).
// Then what a cache line takes to go from one thread's core to the other's (line_ns, one way: two
// threads hand a counter back and forth). Near 25 ns the two CPUs share an L3 cache; a VM whose
// two CPUs the host puts on different L3 caches (a chiplet apart, about 170 ns) gains less from two
// threads on every loop whose threads read what the other wrote, and the three ratios above do not
// show it: they share nothing.
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

double compute_kernel(long iterations) {
  double a = 1.0, b = 1.1, c = 1.2, d = 1.3;
  for (long i = 0; i < iterations; ++i) {
    a = a * 0.999999 + 1e-7;
    b = b * 0.999999 + 1e-7;
    c = c * 0.999999 + 1e-7;
    d = d * 0.999999 + 1e-7;
  }
  return a + b + c + d;
}

double throughput_kernel(long iterations) {
  typedef double Pair __attribute__((vector_size(16)));  // two doubles: SSE2, on every x86-64
  // twelve chains, each in one of the sixteen SSE registers, so that a multiply and an add of
  // another chain fill every cycle a chain waits on its last result
  constexpr int chains = 12;
  Pair a[chains];
  for (int k = 0; k < chains; ++k) a[k] = Pair{1.0, 1.1} + 0.01 * k;
  for (long i = 0; i < iterations; ++i)
#pragma GCC unroll 12  // unrolled, the chains live in registers
    for (int k = 0; k < chains; ++k) a[k] = a[k] * 0.999999 + 1e-7;
  double sum = 0.0;
  for (int k = 0; k < chains; ++k) sum += a[k][0] + a[k][1];
  return sum;
}

double cache_kernel(long sweeps) {
  std::vector<double> x(32768, 1.0);  // 256 KiB
  for (long s = 0; s < sweeps; ++s)
    for (double& v : x) v = v * 0.999999 + 1e-7;
  return x[12345];
}

// Seconds for `total` units of work on `threads` threads, each thread taking total / threads.
template <class Kernel>
double seconds(Kernel kernel, long total, int threads) {
  double sink = 0.0;
  const auto start = std::chrono::steady_clock::now();
#pragma omp parallel num_threads(threads) reduction(+ : sink)
  sink += kernel(total / threads);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (sink == 42.0) std::puts("");  // keeps the work
  return elapsed;
}

// The middle value (the upper of the two middle ones of an even count).
double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

template <class Kernel>
double median_speedup(Kernel kernel, long total, int repeats) {
  std::vector<double> one, two;
  for (int r = 0; r < repeats; ++r) {  // alternating, so a drift in the clock reaches both alike
    one.push_back(seconds(kernel, total, 1));
    two.push_back(seconds(kernel, total, 2));
  }
  return median(one) / median(two);
}

// The counter the two threads hand back and forth, alone in its pair of cache lines (a processor
// may fetch lines in pairs): on the stack, beside the calling thread's locals, it read twice the time.
struct alignas(128) Turn {
  std::atomic<long> value{0};
};
Turn shared_turn;

// Nanoseconds for a cache line to pass from one thread's core to the other's: the median of
// `repeats` runs of 100,000 round trips.
double line_ns(int repeats) {
  std::vector<double> one_way;
  for (int r = 0; r < repeats; ++r) {
    std::atomic<long>& turn = shared_turn.value;
    turn.store(0);
    constexpr long trips = 100'000;
    double elapsed = 0.0;
#pragma omp parallel num_threads(2)
    {
      const long me = omp_get_thread_num();  // thread 0 takes the even turns, thread 1 the odd ones
      if (omp_get_num_threads() == 2) {
#pragma omp barrier
        const auto start = std::chrono::steady_clock::now();
        for (long k = 0; k < 2 * trips; k += 2) {
          const long mine = k + me;
          while (turn.load(std::memory_order_acquire) != mine) {
          }
          turn.store(mine + 1, std::memory_order_release);
        }
        if (me == 0) elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      }
    }
    one_way.push_back(elapsed / (2 * trips) * 1e9);
  }
  return median(one_way);
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  std::printf("compute %.2f\n", median_speedup(compute_kernel, 200'000'000L, repeats));
  std::printf("throughput %.2f\n", median_speedup(throughput_kernel, 40'000'000L, repeats));
  std::printf("cache %.2f\n", median_speedup(cache_kernel, 4'000L, repeats));
  std::printf("line_ns %.0f\n", line_ns(repeats));
  return 0;
}
