#include "rift/io/checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "rift/core/fnv1a.hpp"

namespace rift::io {

namespace {

constexpr char magic[8] = {'R', 'I', 'F', 'T', 'C', 'K', 'P', 'T'};
constexpr char end_mark[8] = {'E', 'N', 'D', 'C', 'K', 'P', 'T', '\0'};
constexpr std::uint32_t format_version = 1;
constexpr std::size_t trailer_bytes = sizeof end_mark + 2 * sizeof(std::uint64_t);

}  // namespace


CheckpointWriter::CheckpointWriter(std::string path, const CheckpointHeader& header)
    : path_(std::move(path)), tmp_path_(path_ + ".tmp"), checksum_(fnv_offset) {
  file_ = std::fopen(tmp_path_.c_str(), "wb");
  if (!file_) throw std::runtime_error("cannot create the checkpoint " + tmp_path_ + ": " + std::strerror(errno));
  const std::uint32_t version = format_version, reserved = 0;
  put(magic, sizeof magic);
  put(&version, sizeof version);
  put(&reserved, sizeof reserved);
  put(&header.scene_fingerprint, sizeof header.scene_fingerprint);
  put(&header.step, sizeof header.step);
  put(&header.time, sizeof header.time);
}

CheckpointWriter::~CheckpointWriter() {
  if (!file_) return;
  std::fclose(file_);
  std::remove(tmp_path_.c_str());
}

void CheckpointWriter::put(const void* data, std::size_t bytes) {
  if (bytes == 0) return;
  if (std::fwrite(data, 1, bytes, file_) != bytes)
    throw std::runtime_error("cannot write the checkpoint " + tmp_path_ + ": " + std::strerror(errno));
  checksum_ = fnv1a(checksum_, data, bytes);
}

void CheckpointWriter::record(const char* name, std::uint64_t element_size, std::uint64_t count, const void* data) {
  const auto length = static_cast<std::uint32_t>(std::strlen(name));
  put(&length, sizeof length);
  put(name, length);
  put(&element_size, sizeof element_size);
  put(&count, sizeof count);
  put(data, static_cast<std::size_t>(element_size * count));
  ++records_;
}

void CheckpointWriter::commit() {
  const std::uint64_t records = records_, checksum = checksum_;
  put(end_mark, sizeof end_mark);
  put(&records, sizeof records);
  put(&checksum, sizeof checksum);
  const bool flushed = std::fflush(file_) == 0 && ::fsync(fileno(file_)) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed) {
    std::remove(tmp_path_.c_str());
    throw std::runtime_error("cannot write the checkpoint " + tmp_path_ + ": " + std::strerror(errno));
  }
  if (std::rename(tmp_path_.c_str(), path_.c_str()) != 0) {
    std::remove(tmp_path_.c_str());
    throw std::runtime_error("cannot rename " + tmp_path_ + " to " + path_ + ": " + std::strerror(errno));
  }
  // the rename itself reaches the disk with its directory
  const auto dir = std::filesystem::path(path_).parent_path();
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

CheckpointReader::CheckpointReader(std::string path) : path_(std::move(path)) {
  file_ = std::fopen(path_.c_str(), "rb");
  if (!file_) throw std::runtime_error("cannot open the checkpoint " + path_ + ": " + std::strerror(errno));
  // the trailer first: a file cut short or damaged anywhere is refused before any record is read
  std::error_code ec;
  const auto size = std::filesystem::file_size(path_, ec);
  const std::size_t head = sizeof magic + 2 * sizeof(std::uint32_t) + sizeof(std::uint64_t) + sizeof(std::int64_t) + sizeof(double);
  if (ec || size < head + trailer_bytes) throw std::runtime_error(path_ + " is not a rift checkpoint (too short)");
  std::array<char, sizeof magic> m{};
  get(m.data(), m.size());
  if (std::memcmp(m.data(), magic, sizeof magic) != 0) throw std::runtime_error(path_ + " is not a rift checkpoint");
  std::uint64_t checksum = fnv_offset;
  std::vector<char> buffer(1 << 20);
  std::fseek(file_, 0, SEEK_SET);
  for (std::uint64_t left = size - trailer_bytes; left > 0;) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(left, buffer.size()));
    get(buffer.data(), n);
    checksum = fnv1a(checksum, buffer.data(), n);
    left -= n;
  }
  std::array<char, sizeof end_mark> e{};
  std::uint64_t stored_checksum = 0;
  get(e.data(), e.size());
  get(&records_, sizeof records_);
  get(&stored_checksum, sizeof stored_checksum);
  if (std::memcmp(e.data(), end_mark, sizeof end_mark) != 0 || stored_checksum != checksum)
    throw std::runtime_error("the checkpoint " + path_ + " is incomplete or damaged (its checksum does not match)");
  std::fseek(file_, static_cast<long>(sizeof magic), SEEK_SET);
  std::uint32_t version = 0, reserved = 0;
  get(&version, sizeof version);
  get(&reserved, sizeof reserved);
  if (version != format_version)
    throw std::runtime_error("the checkpoint " + path_ + " has format version " + std::to_string(version) + "; this rift reads version " +
                             std::to_string(format_version));
  get(&header_.scene_fingerprint, sizeof header_.scene_fingerprint);
  get(&header_.step, sizeof header_.step);
  get(&header_.time, sizeof header_.time);
}

CheckpointReader::~CheckpointReader() {
  if (file_) std::fclose(file_);
}

void CheckpointReader::get(void* data, std::size_t bytes) {
  if (bytes == 0) return;
  if (std::fread(data, 1, bytes, file_) != bytes) throw std::runtime_error("the checkpoint " + path_ + " ends early");
}

void CheckpointReader::record(const char* name, std::uint64_t element_size, std::uint64_t count, void* data, std::uint64_t* count_out) {
  if (records_read_ >= records_)
    throw std::runtime_error("the checkpoint " + path_ + " has no record \"" + name + "\" (written by another version of rift?)");
  std::uint32_t length = 0;
  get(&length, sizeof length);
  std::string stored(length, '\0');
  get(stored.data(), length);
  std::uint64_t stored_size = 0, stored_count = 0;
  get(&stored_size, sizeof stored_size);
  get(&stored_count, sizeof stored_count);
  if (stored != name || stored_size != element_size || (!count_out && stored_count != count))
    throw std::runtime_error("the checkpoint " + path_ + ": record " + std::to_string(records_read_) + " is \"" + stored + "\" (" +
                             std::to_string(stored_count) + " x " + std::to_string(stored_size) + " bytes) where this rift reads \"" +
                             name + "\" (" + std::to_string(element_size) + " bytes each): written by another version of rift?");
  ++records_read_;
  if (count_out) *count_out = stored_count;
  else get(data, static_cast<std::size_t>(element_size * count));
}

void CheckpointReader::read_payload(void* data, std::uint64_t bytes) { get(data, static_cast<std::size_t>(bytes)); }

void CheckpointReader::finish() {
  if (records_read_ != records_)
    throw std::runtime_error("the checkpoint " + path_ + " holds " + std::to_string(records_) + " records; this rift read " +
                             std::to_string(records_read_) + " (written by another version of rift?)");
}

}  // namespace rift::io
