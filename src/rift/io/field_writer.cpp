#include "rift/io/field_writer.hpp"

#include <hdf5.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace rift::io {

FieldWriter::FieldWriter(std::string directory, std::string stem, std::size_t particles, bool together)
    : directory_(std::move(directory)), stem_(std::move(stem)), xdmf_path_(directory_ + "/" + stem_ + ".xdmf"), particles_(particles),
      together_(together) {
  if (together_) {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    index_ = rank == 0;
  }
}

FieldWriter::~FieldWriter() {
  if (file_ < 0) return;  // a snapshot left open by an exception: its temporary file goes
  H5Fclose(file_);
  std::remove((directory_ + "/" + snapshots_.back().file + ".tmp").c_str());
}

void FieldWriter::begin_snapshot(double time) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%06zu.h5", stem_.c_str(), snapshots_.size());
  const std::string tmp = directory_ + "/" + name + ".tmp";
  hid_t properties = H5Pcreate(H5P_FILE_CREATE);
  H5Pset_obj_track_times(properties, false);  // the root group's times
  hid_t access = H5Pcreate(H5P_FILE_ACCESS);
  if (together_) H5Pset_fapl_mpio(access, MPI_COMM_WORLD, MPI_INFO_NULL);  // every rank opens it (collective)
  file_ = H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, properties, access);
  H5Pclose(access);
  H5Pclose(properties);
  if (file_ < 0) throw std::runtime_error("cannot create " + tmp);
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t attr = H5Acreate2(file_, "time", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attr, H5T_NATIVE_DOUBLE, &time);
  H5Aclose(attr);
  H5Sclose(space);
  snapshots_.push_back({time, name, {}});
}

void FieldWriter::write(const std::string& name, const std::vector<double>& values, int components) {
  write_rows(name, values, components, {{0, particles_}});
}

void FieldWriter::write_rows(const std::string& name, const std::vector<double>& values, int components, const std::vector<Rows>& rows) {
  const int rank = components == 1 ? 1 : 2;
  hsize_t dims[2] = {particles_, static_cast<hsize_t>(components)};
  hid_t space = H5Screate_simple(rank, dims, nullptr);
  hid_t properties = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_obj_track_times(properties, false);  // the same fields, the same bytes
  // storage at creation, never filled (every value is written): what MPI-IO takes, and set so for one
  // rank too, whose files are then the same bytes
  H5Pset_alloc_time(properties, H5D_ALLOC_TIME_EARLY);
  H5Pset_fill_time(properties, H5D_FILL_TIME_NEVER);
  hid_t set = H5Dcreate2(file_, name.c_str(), H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, properties, H5P_DEFAULT);
  // this rank's rows of the file, and its values as one block in memory
  std::size_t count = 0;
  H5Sselect_none(space);
  for (const auto& r : rows) {
    if (r.count == 0) continue;
    const hsize_t start[2] = {r.first, 0}, block[2] = {r.count, static_cast<hsize_t>(components)};
    H5Sselect_hyperslab(space, H5S_SELECT_OR, start, nullptr, block, nullptr);
    count += r.count;
  }
  if (values.size() != count * static_cast<std::size_t>(components)) throw std::logic_error("FieldWriter::write_rows: values and rows differ in size");
  hsize_t memory_dims[2] = {count, static_cast<hsize_t>(components)};
  hid_t memory = H5Screate_simple(rank, memory_dims, nullptr);
  if (count == 0) H5Sselect_none(memory);
  hid_t transfer = H5Pcreate(H5P_DATASET_XFER);
  if (together_) H5Pset_dxpl_mpio(transfer, H5FD_MPIO_COLLECTIVE);
  const herr_t written = H5Dwrite(set, H5T_NATIVE_DOUBLE, memory, space, transfer, values.data());
  H5Pclose(transfer);
  H5Sclose(memory);
  H5Dclose(set);
  H5Pclose(properties);
  H5Sclose(space);
  if (set < 0 || written < 0) throw std::runtime_error("cannot write " + name + " to " + directory_ + "/" + snapshots_.back().file + ".tmp");
  snapshots_.back().fields.push_back({name, components});
}

void FieldWriter::end_snapshot() {
  const std::string path = directory_ + "/" + snapshots_.back().file;
  const herr_t closed = H5Fclose(file_);  // (written together: collective, every rank's rows in the file after it)
  file_ = -1;
  if (closed < 0) throw std::runtime_error("cannot write " + path);
  if (!index_) return;
  if (std::rename((path + ".tmp").c_str(), path.c_str()) != 0) throw std::runtime_error("cannot write " + path);
  write_xdmf();
}

void FieldWriter::write_xdmf() const {
  const std::string tmp = xdmf_path_ + ".tmp";
  {
    std::ofstream x(tmp);
    x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (std::size_t k = 0; k < snapshots_.size(); ++k) {
      const auto& s = snapshots_[k];
      x << "   <Grid Name=\"snapshot_" << k << "\" GridType=\"Uniform\">\n";
      x << "    <Time Value=\"" << s.time << "\"/>\n";
      x << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << particles_ << "\" NodesPerElement=\"1\"/>\n";
      x << "    <Geometry GeometryType=\"XYZ\">\n     <DataItem Dimensions=\"" << particles_
        << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << s.file << ":/position</DataItem>\n    </Geometry>\n";
      for (const auto& f : s.fields) {
        if (f.name == "position") continue;
        x << "    <Attribute Name=\"" << f.name << "\" AttributeType=\"" << (f.components == 1 ? "Scalar" : "Vector")
          << "\" Center=\"Node\">\n     <DataItem Dimensions=\"" << particles_;
        if (f.components > 1) x << " " << f.components;
        x << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << s.file << ":/" << f.name << "</DataItem>\n    </Attribute>\n";
      }
      x << "   </Grid>\n";
    }
    x << "  </Grid>\n </Domain>\n</Xdmf>\n";
    x.flush();
    if (!x) throw std::runtime_error("cannot write " + tmp);
  }
  if (std::rename(tmp.c_str(), xdmf_path_.c_str()) != 0) throw std::runtime_error("cannot write " + xdmf_path_);
}

}  // namespace rift::io
