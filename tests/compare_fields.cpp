// compare_fields A B TOLERANCE: whether two runs' outputs agree to a relative tolerance, for the
// distributed runs whose sums add the same terms in another order than one rank's (mpm/domain.hpp).
// A and B are two output directories: every snapshot fields_*.h5 of A (each dataset, and the time)
// and history.csv and crack_tips.csv (each column) against B's. A field agrees when max |a - b| <= TOLERANCE * max |a|,
// the maxima over every snapshot of the run: the difference relative to the field's size in the
// run, as a value near zero (the stress of a body in free flight: round-off) has no relative error
// of its own. Exit status 0 when everything agrees, 1 otherwise (each field that differs printed),
// 2 on a missing or unreadable file.
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Worst {
  std::string name;
  double error = 0.0, scale = 0.0;
  std::size_t worst_at = 0;  // the value that differs most, in its snapshot's dataset (row-major)
  // a column of a CSV file, printed to 10 significant digits (history.csv, io/history.cpp) or 9
  // (crack_tips.csv; its angle 6): one unit in the last digit, 1e-9 or 1e-8 of the value, is the best it can agree
  double printed = 0.0;
  bool agrees(double tolerance) const { return error <= std::max(tolerance, printed) * scale; }
  /// Takes in another snapshot's values of the field.
  void add(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size()) error = INFINITY;
    for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
      scale = std::max(scale, std::abs(a[k]));
      const double d = std::isnan(a[k] - b[k]) ? INFINITY : std::abs(a[k] - b[k]);
      if (d > error) error = d, worst_at = k;
    }
  }
};

/// The field called `name` in `fields` (made on first sight).
Worst& field(std::vector<Worst>& fields, const std::string& name) {
  for (auto& f : fields)
    if (f.name == name) return f;
  return fields.emplace_back(Worst{name});
}

std::vector<double> read_dataset(hid_t file, const std::string& name) {
  hid_t set = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  if (set < 0) return {};
  hid_t space = H5Dget_space(set);
  std::vector<double> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Sclose(space);
  H5Dclose(set);
  return values;
}

double read_time(hid_t file) {
  double t = NAN;
  hid_t attr = H5Aopen(file, "time", H5P_DEFAULT);
  if (attr < 0) return t;
  H5Aread(attr, H5T_NATIVE_DOUBLE, &t);
  H5Aclose(attr);
  return t;
}

void compare_h5(const std::string& a_path, const std::string& b_path, std::vector<Worst>& fields) {
  hid_t a = H5Fopen(a_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), b = H5Fopen(b_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (a < 0 || b < 0) throw std::runtime_error("cannot open " + (a < 0 ? a_path : b_path));
  std::vector<std::string> names;
  H5Literate(a, H5_INDEX_NAME, H5_ITER_NATIVE, nullptr,
              [](hid_t, const char* name, const H5L_info_t*, void* out) {
                static_cast<std::vector<std::string>*>(out)->push_back(name);
                return herr_t(0);
              },
              &names);
  field(fields, "time").add({read_time(a)}, {read_time(b)});
  for (const auto& n : names) field(fields, n).add(read_dataset(a, n), read_dataset(b, n));
  H5Fclose(a);
  H5Fclose(b);
}

/// A CSV file's columns, each cell a number (NaN where it is text: compared as text).
std::vector<std::vector<std::string>> read_csv(const std::string& path, std::vector<std::string>& header) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::string line, cell;
  std::getline(in, line);
  std::stringstream h(line);
  while (std::getline(h, cell, ',')) header.push_back(cell);
  std::vector<std::vector<std::string>> columns(header.size());
  while (std::getline(in, line)) {
    std::stringstream r(line);
    for (std::size_t c = 0; c < header.size() && std::getline(r, cell, ','); ++c) columns[c].push_back(cell);
  }
  return columns;
}

void compare_csv(const std::string& a_path, const std::string& b_path, std::vector<Worst>& columns) {
  std::vector<std::string> ha, hb;
  const auto a = read_csv(a_path, ha), b = read_csv(b_path, hb);
  if (ha != hb) throw std::runtime_error(a_path + " and " + b_path + " have different columns");
  const std::string file = std::filesystem::path(a_path).filename().string();
  for (std::size_t c = 0; c < ha.size(); ++c) {
    auto& column = field(columns, file + " " + ha[c]);
    column.printed = file != "crack_tips.csv" ? 1e-9 : ha[c] == "angle_deg" ? 1e-5 : 1e-8;  // the angle: 6 digits
    std::vector<double> x, y;
    for (std::size_t k = 0; k < std::min(a[c].size(), b[c].size()); ++k) {
      char* end = nullptr;
      const double u = std::strtod(a[c][k].c_str(), &end);
      if (end == a[c][k].c_str() || *end) {  // text
        if (a[c][k] != b[c][k]) column.error = INFINITY;
        continue;
      }
      x.push_back(u), y.push_back(std::strtod(b[c][k].c_str(), nullptr));
    }
    if (a[c].size() != b[c].size()) column.error = INFINITY;
    column.add(x, y);
  }
  // crack_tips.csv: a quantity's size is its family's (J_1, J_2 and J_1_area; K_I, K_II and their
  // splits): J_2 and K_II of a mode-I crack are round-off of J_1 and K_I, with no size of their own
  if (file != "crack_tips.csv") return;
  for (const auto& ca : ha)
    for (const auto& cb : ha) {
      const auto family = [](const std::string& n) { return n.substr(0, n.find('_')); };
      if (ca.find('_') == std::string::npos || family(ca) != family(cb)) continue;
      auto& a_column = field(columns, file + " " + ca);
      a_column.scale = std::max(a_column.scale, field(columns, file + " " + cb).scale);
    }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: compare_fields DIR_A DIR_B TOLERANCE (two runs' output directories)\n");
    return 2;
  }
  const std::string a = argv[1], b = argv[2];
  const double tolerance = std::stod(argv[3]);
  try {
    std::vector<Worst> fields;
    std::size_t snapshots = 0;
    for (;; ++snapshots) {
      char name[64];
      std::snprintf(name, sizeof name, "/fields_%06zu.h5", snapshots);
      if (!std::filesystem::exists(a + name)) break;
      if (!std::filesystem::exists(b + name)) throw std::runtime_error(b + name + " is missing");
      compare_h5(a + name, b + name, fields);
    }
    char next[64];
    std::snprintf(next, sizeof next, "/fields_%06zu.h5", snapshots);
    if (snapshots == 0 || std::filesystem::exists(b + next)) throw std::runtime_error("the runs have different snapshots");
    compare_csv(a + "/history.csv", b + "/history.csv", fields);
    if (std::filesystem::exists(a + "/crack_tips.csv")) compare_csv(a + "/crack_tips.csv", b + "/crack_tips.csv", fields);
    bool ok = true;
    for (const auto& w : fields) {
      if (w.agrees(tolerance)) continue;
      std::printf("%s vs %s: %s differs by %.3g at value %zu (its largest value %.3g, tolerance %.3g relative)\n", a.c_str(), b.c_str(),
                  w.name.c_str(), w.error, w.worst_at, w.scale, tolerance);
      ok = false;
    }
    std::printf("%s vs %s: %zu snapshots and the history %s to %g relative\n", a.c_str(), b.c_str(), snapshots, ok ? "agree" : "do not agree",
                tolerance);
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "compare_fields: %s\n", e.what());
    return 2;
  }
}
