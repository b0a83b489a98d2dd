// rift-validate [--quick] [--output DIR] [CASE...]: runs validation cases (all by default) and
// prints one line per case:  CASE PASS|FAIL measured=... reference=... tolerance=...
// Exit status 0 when every case passes, 1 otherwise, 2 for an unknown case.
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "cases/case.hpp"
#include "rift/parallel/cpu_quota.hpp"

int main(int argc, char** argv) {
  rift::parallel::limit_threads_to_cpu_quota();
  rift::validation::Settings settings;
  settings.quick = false;
  std::vector<std::string> names;
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--quick")) settings.quick = true;
    else if (!std::strcmp(argv[a], "--output") && a + 1 < argc) settings.output_dir = argv[++a];
    else if (!std::strcmp(argv[a], "--list")) {
      for (const auto& c : rift::validation::all_cases()) std::printf("%s\n", c.name);
      return 0;
    } else names.push_back(argv[a]);
  }
  if (!settings.output_dir.empty()) std::filesystem::create_directories(settings.output_dir);
  const auto& cases = rift::validation::all_cases();
  if (names.empty())
    for (const auto& c : cases) names.push_back(c.name);
  bool all_pass = true;
  for (const auto& name : names) {
    const rift::validation::Entry* entry = nullptr;
    for (const auto& c : cases)
      if (name == c.name) entry = &c;
    if (!entry) {
      std::fprintf(stderr, "rift-validate: unknown case '%s' (--list shows them)\n", name.c_str());
      return 2;
    }
    rift::validation::Result r;
    try {
      r = entry->run(settings);
    } catch (const std::exception& e) {  // a case that cannot finish fails with the reason
      r.name = name;
      r.pass = false;
      r.details = std::string("stopped: ") + e.what();
    }
    all_pass = all_pass && r.pass;
    std::printf("%s %s measured=%.6g reference=%.6g tolerance=%.6g unit=\"%s\" details=\"%s\" source=\"%s\"\n", name.c_str(),
                r.pass ? "PASS" : "FAIL", r.measured, r.reference, r.tolerance, r.unit.c_str(), r.details.c_str(), r.source.c_str());
    std::fflush(stdout);
  }
  return all_pass ? 0 : 1;
}
