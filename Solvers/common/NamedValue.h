// One named value a solver reports beside its particles (a run's clock, conserved totals,
// set-up figures): a number, a vector, a text or a series. The filters write a list of them,
// in order, as field data; the list is plain data so that it carries no VTK.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace craterkit {

struct NamedValue {
  std::string name;
  // A number or vector: one tuple of values.size() components. A series: one number per entry.
  std::vector<double> values;
  std::string text;
  bool isText = false;
  bool isSeries = false;

  static NamedValue number(std::string name, double value) {
    return NamedValue{std::move(name), {value}, "", false, false};
  }
  static NamedValue vector(std::string name, std::vector<double> values) {
    return NamedValue{std::move(name), std::move(values), "", false, false};
  }
  static NamedValue string(std::string name, std::string text) {
    return NamedValue{std::move(name), {}, std::move(text), true, false};
  }
  static NamedValue series(std::string name, std::vector<double> values) {
    return NamedValue{std::move(name), std::move(values), "", false, true};
  }
};

} // namespace craterkit
