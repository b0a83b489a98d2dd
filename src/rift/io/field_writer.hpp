// Particle fields per snapshot in one HDF5 file, with an XDMF index so ParaView/VisIt open the
// time series directly (Polyvertex topology; 2D positions are padded with z = 0).
#pragma once
#include <string>
#include <vector>

namespace rift::io {

class FieldWriter {
 public:
  FieldWriter(std::string directory, std::string stem, std::size_t particles);
  ~FieldWriter();
  FieldWriter(const FieldWriter&) = delete;
  FieldWriter& operator=(const FieldWriter&) = delete;

  void begin_snapshot(double time);
  /// A field with `components` values per particle (1 = scalar, 3 = vector), row-major.
  void write(const std::string& name, const std::vector<double>& values, int components);
  void end_snapshot();
  const std::string& h5_path() const { return h5_path_; }
  const std::string& xdmf_path() const { return xdmf_path_; }

 private:
  void write_xdmf() const;
  struct Field {
    std::string name;
    int components;
  };
  struct Snapshot {
    double time;
    std::string group;
    std::vector<Field> fields;
  };
  std::string h5_path_, xdmf_path_, h5_name_;
  std::size_t particles_;
  long long file_ = -1, group_ = -1;
  std::vector<Snapshot> snapshots_;
};

}  // namespace rift::io
