#include "rift/io/history.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace rift::io {

History::History(const std::string& path, std::vector<std::string> columns) : path_(path) {
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) throw std::runtime_error("cannot create " + path);
  for (std::size_t i = 0; i < columns.size(); ++i) std::fprintf(file_, "%s%s", i ? "," : "", columns[i].c_str());
  std::fprintf(file_, "\n");
}

History::History(const std::string& path, std::int64_t bytes) : path_(path) {
  file_ = std::fopen(path.c_str(), "r+");
  if (!file_ || std::fseek(file_, 0, SEEK_END) != 0 || std::ftell(file_) < bytes || ::ftruncate(fileno(file_), bytes) != 0 ||
      std::fseek(file_, bytes, SEEK_SET) != 0)
    throw std::runtime_error("cannot continue " + path + " from its first " + std::to_string(bytes) + " bytes (the checkpoint's): " +
                             (file_ ? "it is shorter" : std::strerror(errno)));
}

std::int64_t History::bytes() const { return static_cast<std::int64_t>(std::ftell(file_)); }

History::~History() {
  if (file_) std::fclose(file_);
}

void History::row(const std::vector<double>& values) {
  for (std::size_t i = 0; i < values.size(); ++i) std::fprintf(file_, "%s%.10g", i ? "," : "", values[i]);
  std::fprintf(file_, "\n");
  std::fflush(file_);
}

}  // namespace rift::io
