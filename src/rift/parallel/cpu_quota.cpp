#include "rift/parallel/cpu_quota.hpp"

#include <omp.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

namespace rift::parallel {

namespace {

// CPUs for a quota of `quota` microseconds per `period`; 0 when either is not positive.
int cpus_for(double quota, double period) {
  if (!(quota > 0.0) || !(period > 0.0)) return 0;
  return std::max(1, static_cast<int>(std::ceil(quota / period)));
}

}  // namespace

int cpu_quota() {
  // cgroup v2: one line "<quota> <period>", with "max" for no quota.
  if (std::ifstream v2("/sys/fs/cgroup/cpu.max"); v2) {
    std::string quota;
    double period = 0.0;
    if (v2 >> quota >> period) {
      if (quota == "max") return 0;
      return cpus_for(std::atof(quota.c_str()), period);
    }
  }
  // cgroup v1: the quota is -1 when there is none.
  std::ifstream q("/sys/fs/cgroup/cpu/cpu.cfs_quota_us"), p("/sys/fs/cgroup/cpu/cpu.cfs_period_us");
  double quota = 0.0, period = 0.0;
  if (q >> quota && p >> period) return cpus_for(quota, period);
  return 0;
}

void limit_threads_to_cpu_quota() {
  if (std::getenv("OMP_NUM_THREADS") != nullptr) return;
  const int cpus = cpu_quota();
  if (cpus > 0 && cpus < omp_get_max_threads()) omp_set_num_threads(cpus);
}

}  // namespace rift::parallel
