#include "rift/io/history.hpp"

#include <stdexcept>

namespace rift::io {

History::History(const std::string& path, std::vector<std::string> columns) : path_(path) {
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) throw std::runtime_error("cannot create " + path);
  for (std::size_t i = 0; i < columns.size(); ++i) std::fprintf(file_, "%s%s", i ? "," : "", columns[i].c_str());
  std::fprintf(file_, "\n");
}

History::~History() {
  if (file_) std::fclose(file_);
}

void History::row(const std::vector<double>& values) {
  for (std::size_t i = 0; i < values.size(); ++i) std::fprintf(file_, "%s%.10g", i ? "," : "", values[i]);
  std::fprintf(file_, "\n");
  std::fflush(file_);
}

}  // namespace rift::io
