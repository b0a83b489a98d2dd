// CSV history: one row per history time (time, energies, broken bonds, reaction forces, ...).
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace rift::io {

class History {
 public:
  History(const std::string& path, std::vector<std::string> columns);
  /// Continues the file of a restarted run: keeps its first `bytes` (the header and the rows up to
  /// the checkpoint; a row the interrupted run wrote after it goes) and appends to them.
  History(const std::string& path, std::int64_t bytes);
  ~History();
  History(const History&) = delete;
  History& operator=(const History&) = delete;
  void row(const std::vector<double>& values);
  const std::string& path() const { return path_; }
  /// The file's length so far (every row is flushed as written).
  std::int64_t bytes() const;

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
};

}  // namespace rift::io
