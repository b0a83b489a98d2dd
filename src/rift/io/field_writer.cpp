#include "rift/io/field_writer.hpp"

#include <hdf5.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace rift::io {

FieldWriter::FieldWriter(std::string directory, std::string stem, std::size_t particles)
    : h5_path_(directory + "/" + stem + ".h5"), xdmf_path_(directory + "/" + stem + ".xdmf"), h5_name_(stem + ".h5"),
      particles_(particles) {
  file_ = H5Fcreate(h5_path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file_ < 0) throw std::runtime_error("cannot create " + h5_path_);
}

FieldWriter::~FieldWriter() {
  if (group_ >= 0) H5Gclose(group_);
  if (file_ >= 0) H5Fclose(file_);
}

void FieldWriter::begin_snapshot(double time) {
  char name[32];
  std::snprintf(name, sizeof name, "snapshot_%06zu", snapshots_.size());
  group_ = H5Gcreate2(file_, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t attr = H5Acreate2(group_, "time", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attr, H5T_NATIVE_DOUBLE, &time);
  H5Aclose(attr);
  H5Sclose(space);
  snapshots_.push_back({time, name, {}});
}

void FieldWriter::write(const std::string& name, const std::vector<double>& values, int components) {
  hsize_t dims[2] = {particles_, static_cast<hsize_t>(components)};
  hid_t space = H5Screate_simple(components == 1 ? 1 : 2, dims, nullptr);
  hid_t set = H5Dcreate2(group_, name.c_str(), H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Dclose(set);
  H5Sclose(space);
  snapshots_.back().fields.push_back({name, components});
}

void FieldWriter::end_snapshot() {
  H5Gclose(group_);
  group_ = -1;
  H5Fflush(file_, H5F_SCOPE_GLOBAL);
  write_xdmf();
}

void FieldWriter::write_xdmf() const {
  std::ofstream x(xdmf_path_);
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& s : snapshots_) {
    x << "   <Grid Name=\"" << s.group << "\" GridType=\"Uniform\">\n";
    x << "    <Time Value=\"" << s.time << "\"/>\n";
    x << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << particles_ << "\" NodesPerElement=\"1\"/>\n";
    x << "    <Geometry GeometryType=\"XYZ\">\n     <DataItem Dimensions=\"" << particles_
      << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5_name_ << ":/" << s.group << "/position</DataItem>\n    </Geometry>\n";
    for (const auto& f : s.fields) {
      if (f.name == "position") continue;
      x << "    <Attribute Name=\"" << f.name << "\" AttributeType=\"" << (f.components == 1 ? "Scalar" : "Vector")
        << "\" Center=\"Node\">\n     <DataItem Dimensions=\"" << particles_;
      if (f.components > 1) x << " " << f.components;
      x << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5_name_ << ":/" << s.group << "/" << f.name
        << "</DataItem>\n    </Attribute>\n";
    }
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
}

}  // namespace rift::io
