// CSV history: one row per history time (time, energies, broken bonds, reaction forces, ...).
#pragma once
#include <cstdio>
#include <string>
#include <vector>

namespace rift::io {

class History {
 public:
  History(const std::string& path, std::vector<std::string> columns);
  ~History();
  History(const History&) = delete;
  History& operator=(const History&) = delete;
  void row(const std::vector<double>& values);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
};

}  // namespace rift::io
