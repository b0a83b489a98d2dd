// Checkpoint files: a run's whole state, to continue it bit for bit (`rift run SCENE --restart FILE`).
//
// A checkpoint is a sequence of named records (name, element size, count, bytes), between a header
// (magic, format version, the scene's fingerprint, the run's step) and a trailer (record count and a
// 64-bit FNV-1a checksum of everything before it). Raw bytes keep every double exact. It is written to
// FILE.tmp, flushed to the disk and renamed over FILE (POSIX rename is atomic), so a run killed at
// any moment leaves the last complete checkpoint. LAMMPS' write_restart is a binary image of the
// same kind; a checkpoint is read only by the build that wrote it (same layout of every record).
//
// One function lists a state's records for both directions: `visit(archive, state)` calls
// archive("name", member) for every member, and CheckpointWriter writes them where
// CheckpointReader reads them back into the same members, checking each name, size and count.
#pragma once
#include <Eigen/Core>

#include <cstdint>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

namespace rift::io {

/// A struct that lists its members for the checkpoint (`visit(archive, x)`, found by argument-
/// dependent lookup): written member by member. Other trivially copyable types are written as
/// their bytes, so a struct with padding (whose bytes are indeterminate) lists its members, and
/// the same state gives the same file.
template <class Archive, class T>
concept visitable = requires(Archive& a, T& t) { visit(a, t); };

/// Types written as their bytes: the trivially copyable ones, and those a header declares so (a
/// fixed-size Eigen matrix is its coefficients alone, though its copy is user-provided).
template <class T>
struct written_as_bytes : std::is_trivially_copyable<T> {};
/// A fixed-size Eigen matrix (the material point method's state) is its coefficients, column after
/// column, and nothing else.
template <class Scalar, int Rows, int Cols, int Options, int MaxRows, int MaxCols>
  requires(Rows > 0 && Cols > 0)
struct written_as_bytes<Eigen::Matrix<Scalar, Rows, Cols, Options, MaxRows, MaxCols>> : std::true_type {
  static_assert(sizeof(Eigen::Matrix<Scalar, Rows, Cols, Options, MaxRows, MaxCols>) == sizeof(Scalar) * Rows * Cols);
};

namespace detail {
template <class T>
struct is_vector : std::false_type {};
template <class T, class A>
struct is_vector<std::vector<T, A>> : std::true_type {};
/// A vector's elements go one by one (a count record, then each) unless they are written as bytes
/// together in one record.
template <class Archive, class E>
inline constexpr bool one_by_one = is_vector<E>::value || visitable<Archive, E> || !written_as_bytes<E>::value;
}  // namespace detail

/// What a checkpoint says of itself, checked against the scene before anything is read.
struct CheckpointHeader {
  std::uint64_t scene_fingerprint = 0;  // scene::Scene::fingerprint
  std::int64_t step = 0;                // the steps (or load steps) completed
  double time = 0.0;                    // the model's time then, s
};

class CheckpointWriter {
 public:
  /// Opens path + ".tmp"; nothing is at `path` until commit().
  CheckpointWriter(std::string path, const CheckpointHeader& header);
  ~CheckpointWriter();  // without commit(): removes the temporary file
  CheckpointWriter(const CheckpointWriter&) = delete;
  CheckpointWriter& operator=(const CheckpointWriter&) = delete;

  template <class T>
  void operator()(const char* name, const T& value) {
    if constexpr (detail::is_vector<T>::value) {
      using E = typename T::value_type;
      if constexpr (detail::one_by_one<CheckpointWriter, E>) {
        std::uint64_t count = value.size();
        record(name, sizeof count, 1, &count);
        for (const auto& e : value) (*this)(name, e);
      } else {
        record(name, sizeof(E), value.size(), value.data());
      }
    } else if constexpr (std::is_same_v<T, std::string>) {
      record(name, 1, value.size(), value.data());
    } else if constexpr (visitable<CheckpointWriter, T>) {
      visit(*this, const_cast<T&>(value));  // a struct of records
    } else {
      static_assert(written_as_bytes<T>::value, "a struct in a checkpoint lists its members with visit()");
      record(name, sizeof(T), 1, &value);
    }
  }
  /// Writes the trailer, flushes the file to the disk and renames it to the path.
  void commit();

 private:
  void record(const char* name, std::uint64_t element_size, std::uint64_t count, const void* data);
  void put(const void* data, std::size_t bytes);
  std::string path_, tmp_path_;
  std::FILE* file_ = nullptr;
  std::uint64_t checksum_ = 0, records_ = 0;
};

class CheckpointReader {
 public:
  /// Opens the file and checks its magic, version, trailer and checksum (a truncated or damaged
  /// file is refused here, whole); throws std::runtime_error with the reason.
  explicit CheckpointReader(std::string path);
  ~CheckpointReader();
  CheckpointReader(const CheckpointReader&) = delete;
  CheckpointReader& operator=(const CheckpointReader&) = delete;

  const CheckpointHeader& header() const { return header_; }
  const std::string& path() const { return path_; }

  template <class T>
  void operator()(const char* name, T& value) {
    if constexpr (detail::is_vector<T>::value) {
      using E = typename T::value_type;
      if constexpr (detail::one_by_one<CheckpointReader, E>) {
        std::uint64_t count = 0;
        record(name, sizeof count, 1, &count, nullptr);
        value.resize(count);
        for (auto& e : value) (*this)(name, e);
      } else {
        std::uint64_t count = 0;
        record(name, sizeof(E), count, nullptr, &count);
        value.resize(count);
        read_payload(value.data(), count * sizeof(E));
      }
    } else if constexpr (std::is_same_v<T, std::string>) {
      std::uint64_t count = 0;
      record(name, 1, 0, nullptr, &count);
      value.resize(count);
      read_payload(value.data(), count);
    } else if constexpr (visitable<CheckpointReader, T>) {
      visit(*this, value);
    } else {
      static_assert(written_as_bytes<T>::value, "a struct in a checkpoint lists its members with visit()");
      record(name, sizeof(T), 1, &value, nullptr);
    }
  }
  /// Checks that every record was read.
  void finish();

 private:
  /// Reads a record's head and checks its name and element size; with count_out, returns its count
  /// and leaves the payload to read_payload; else reads `count` elements into data.
  void record(const char* name, std::uint64_t element_size, std::uint64_t count, void* data, std::uint64_t* count_out);
  void read_payload(void* data, std::uint64_t bytes);
  void get(void* data, std::size_t bytes);
  std::string path_;
  std::FILE* file_ = nullptr;
  CheckpointHeader header_;
  std::uint64_t records_ = 0, records_read_ = 0;
};

}  // namespace rift::io
