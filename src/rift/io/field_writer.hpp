// Particle fields per snapshot, one HDF5 file each (stem_000000.h5, ...), with an XDMF index so
// ParaView/VisIt open the time series directly (Polyvertex topology; 2D positions are padded with
// z = 0). Each file is written under a temporary name and renamed once closed, and so is the index:
// a run killed at any moment leaves every snapshot the index lists whole, and no half-written file
// under a snapshot's name. The files carry no object times, so the same run writes the same bytes.
#pragma once
#include <string>
#include <vector>

namespace rift::io {

class FieldWriter {
 public:
  /// together: the ranks of a distributed run write each snapshot file together (HDF5 over MPI-IO),
  /// each its own rows (write_rows); every rank then makes every call, and rank 0 the XDMF index.
  FieldWriter(std::string directory, std::string stem, std::size_t particles, bool together = false);
  ~FieldWriter();
  FieldWriter(const FieldWriter&) = delete;
  FieldWriter& operator=(const FieldWriter&) = delete;

  void begin_snapshot(double time);
  /// A field with `components` values per particle (1 = scalar, 3 = vector), row-major.
  void write(const std::string& name, const std::vector<double>& values, int components);
  /// Particles [first, first + count) of the whole run.
  struct Rows {
    std::size_t first = 0, count = 0;
  };
  /// This rank's part of a field: `values` holds the rows of `rows`, one after the other (written
  /// together: every rank calls it with its own).
  void write_rows(const std::string& name, const std::vector<double>& values, int components, const std::vector<Rows>& rows);
  void end_snapshot();
  /// The snapshots' files: stem_??????.h5 in the directory.
  std::string h5_pattern() const { return directory_ + "/" + stem_ + "_??????.h5"; }
  const std::string& xdmf_path() const { return xdmf_path_; }

  /// The index of the snapshots written so far, for a checkpoint (pd/checkpoint_state.hpp): a
  /// restart takes it back and goes on numbering, its index listing the earlier snapshots too.
  template <class A>
  void visit_state(A& a) {
    a("fields.snapshots", snapshots_);
  }

 private:
  struct Field {
    std::string name;
    int components = 1;
    template <class A>
    friend void visit(A& a, Field& f) {
      a("field.name", f.name), a("field.components", f.components);
    }
  };
  struct Snapshot {
    double time = 0.0;
    std::string file;  // its file's name in the directory
    std::vector<Field> fields;
    template <class A>
    friend void visit(A& a, Snapshot& s) {
      a("snapshot.time", s.time), a("snapshot.file", s.file), a("snapshot.fields", s.fields);
    }
  };
  void write_xdmf() const;
  std::string directory_, stem_, xdmf_path_;
  std::size_t particles_;
  bool together_ = false;
  bool index_ = true;  // this rank writes the XDMF index and names the files (rank 0)
  long long file_ = -1;
  std::vector<Snapshot> snapshots_;
};

}  // namespace rift::io
