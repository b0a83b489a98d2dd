// OpenMP's default team is one thread per CPU the process may run on, but a container limited by
// a CFS CPU quota (cgroup cpu.max, e.g. "200000 100000" = 2 CPUs) still sees every CPU of its
// host. A team of 64 threads on 2 CPUs' worth of time spins in its barriers and runs many times
// slower than 2 threads. Unless the user set OMP_NUM_THREADS, the team is capped at the quota.
#pragma once

namespace rift::parallel {

/// CPUs granted by the cgroup CPU quota (v2 cpu.max, else v1 cpu.cfs_quota_us / cfs_period_us),
/// rounded up; 0 where there is no quota or it cannot be read.
int cpu_quota();

/// Caps omp_get_max_threads() at cpu_quota() when OMP_NUM_THREADS is not set. Call once, at the
/// start of main.
void limit_threads_to_cpu_quota();

}  // namespace rift::parallel
