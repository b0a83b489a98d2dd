// The outcome at each interface over a run (interface_outcome.hpp), as a cut block shows it: recorded
// at each history row up to the row where a fluid first broke through to the outer surface (a
// laboratory test ends there, its pressure lost; the load step's bonds stop breaking then,
// pd/dynamic_relaxation.hpp), and when it broke through. A checkpoint holds it with the run.
#pragma once
#include <string>
#include <vector>

#include "rift/geomech/interface_outcome.hpp"

namespace rift::geomech {

struct InterfaceRecord {
  std::vector<InterfaceOutcome> outcomes, at_breakthrough;
  double vent_time = -1.0;  // when a fluid first broke through, s; negative: not yet

  /// The history's columns: four per interface.
  static std::vector<std::string> column_names(std::size_t interfaces) {
    std::vector<std::string> names;
    for (std::size_t k = 0; k < interfaces; ++k)
      for (const char* q : {"crossed", "dilated", "crossing_distance", "opened_length"})
        names.push_back(std::string(q) + "_interface_" + std::to_string(k));
    return names;
  }
  /// A run that starts (not a restart): the initial state's outcome.
  template <int D>
  void start(const Model<D>& m) {
    record_outcomes(outcomes, classify_interfaces<D>(m));
    at_breakthrough = outcomes;
  }
  /// A history row at time t (`vented`: a fluid has broken through by now): the outcome recorded,
  /// its columns appended to `row`.
  template <int D>
  void row(const Model<D>& m, double t, bool vented, std::vector<double>& row) {
    record_outcomes(outcomes, classify_interfaces<D>(m));
    for (const auto& o : outcomes) row.insert(row.end(), {double(o.crossed), double(o.dilated), o.crossing_distance, o.opened_length});
    if (vent_time < 0.0) at_breakthrough = outcomes;
    if (vented && vent_time < 0.0) vent_time = t;
  }
  /// The outcomes a run ends with: as they were when a fluid broke through, else as the model ends.
  template <int D>
  const std::vector<InterfaceOutcome>& final_outcomes(const Model<D>& m) {
    if (vent_time < 0.0) record_outcomes(outcomes, classify_interfaces<D>(m));
    return vent_time < 0.0 ? outcomes : at_breakthrough;
  }
  /// The checkpoint's records.
  template <class A>
  void visit(A& a) {
    a("run.outcomes", outcomes), a("run.outcomes_at_breakthrough", at_breakthrough), a("run.vent_time", vent_time);
  }
};

}  // namespace rift::geomech
