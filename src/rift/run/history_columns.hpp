// The columns of a run's history.csv: time and step, then each provider's group in the order the
// runner adds them (the energies, probes, fluids, interfaces, reactions, the solver's own), with
// their names given once and their values appended at each row. A provider with no column still
// runs at each row, so that what it records between rows (an interface's outcome) keeps its cadence.
#pragma once
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace rift::run {

class HistoryColumns {
 public:
  using Values = std::function<void(std::vector<double>& row)>;
  void add(std::vector<std::string> names, Values values) {
    names_.insert(names_.end(), names.begin(), names.end());
    providers_.push_back(std::move(values));
  }
  /// time, step, then every provider's names.
  std::vector<std::string> names() const {
    std::vector<std::string> all{"time", "step"};
    all.insert(all.end(), names_.begin(), names_.end());
    return all;
  }
  /// The row of (time, step): each provider's values in turn.
  std::vector<double> row(double time, long step) const {
    std::vector<double> r{time, double(step)};
    for (const auto& values : providers_) values(r);
    return r;
  }

 private:
  std::vector<std::string> names_;
  std::vector<Values> providers_;
};

}  // namespace rift::run
