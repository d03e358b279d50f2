#pragma once
// A Config struct's tunable fields, declared once: the name (the ROS parameter and the tool
// option), the member it sets, the allowed range and a one-line doc with the unit. The defaults
// stay in the struct's member initialisers; from the table come
//   - the Config's validate() (Fields::validate: the first field out of range is named),
//   - a node's parameter loading (ros/config_params.h: loadFields),
//   - the tools' options (src/tools/command_line.h: CommandLine::fields),
//   - the parameter table of each node's doc page (describe_parameters, checked by
//     parameters_documented_test).
// Nested configs are folded in with nest(), their parameter names unchanged (flat, as ROS users
// know them).
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace adaptive_perception::config {

enum class Kind { kInt, kDouble, kBool };

/// The allowed values of a number: lo..hi, an open end excluding its bound.
struct Range {
  double lo = 0.0, hi = 0.0;
  bool lo_open = false, hi_open = false;
  bool contains(double v) const {
    return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string text() const;  // "[0, 1)"
};
inline Range closed(double lo, double hi) { return {lo, hi, false, false}; }
inline Range aboveZero(double hi) { return {0.0, hi, true, false}; }  // (0, hi]
inline Range belowOne() { return {0.0, 1.0, false, true}; }           // [0, 1)

/// A value as it reads in a message or a table: integers without a decimal point, booleans as
/// true / false, reals in the shortest form that reads back the same.
std::string formatValue(Kind kind, double v);
inline std::string formatReal(double v) { return formatValue(Kind::kDouble, v); }
/// A list as a table shows it: "[a, b]" (numbers as formatValue writes reals).
std::string formatList(const std::vector<std::string>& items);
std::string formatList(const std::vector<double>& numbers);

template <class C>
struct Field {
  std::string name;
  Kind kind;
  Range range;
  std::string doc;
  std::function<double(const C&)> get;
  std::function<void(C&, double)> set;
};

template <class C>
class Fields {
 public:
  Fields& add(std::string name, int C::*m, Range range, std::string doc) {
    return push(
        std::move(name), Kind::kInt, range, std::move(doc),
        [m](const C& c) { return static_cast<double>(c.*m); },
        [m](C& c, double v) { c.*m = static_cast<int>(v); });
  }
  Fields& add(std::string name, double C::*m, Range range, std::string doc) {
    return push(
        std::move(name), Kind::kDouble, range, std::move(doc), [m](const C& c) { return c.*m; },
        [m](C& c, double v) { c.*m = v; });
  }
  Fields& add(std::string name, bool C::*m, std::string doc) {
    return push(
        std::move(name), Kind::kBool, closed(0, 1), std::move(doc),
        [m](const C& c) { return c.*m ? 1.0 : 0.0; }, [m](C& c, double v) { c.*m = v != 0.0; });
  }
  /// A member of a member (a nested config that has no table of its own).
  template <class S, class T>
  Fields& add(std::string name, S C::*sub, T S::*m, Range range, std::string doc) {
    static_assert(std::is_same_v<T, double> || std::is_same_v<T, int>);
    return push(
        std::move(name), std::is_same_v<T, int> ? Kind::kInt : Kind::kDouble, range, std::move(doc),
        [sub, m](const C& c) { return static_cast<double>(c.*sub.*m); },
        [sub, m](C& c, double v) { c.*sub.*m = static_cast<T>(v); });
  }
  /// A boolean member of a member.
  template <class S>
  Fields& add(std::string name, S C::*sub, bool S::*m, std::string doc) {
    return push(
        std::move(name), Kind::kBool, closed(0, 1), std::move(doc),
        [sub, m](const C& c) { return c.*sub.*m ? 1.0 : 0.0; },
        [sub, m](C& c, double v) { c.*sub.*m = v != 0.0; });
  }
  /// Every field of a nested config's table.
  template <class S>
  Fields& nest(S C::*sub, const Fields<S>& inner) {
    for (const Field<S>& f : inner.all())
      push(
          f.name, f.kind, f.range, f.doc, [sub, g = f.get](const C& c) { return g(c.*sub); },
          [sub, s = f.set](C& c, double v) { s(c.*sub, v); });
    return *this;
  }

  const std::vector<Field<C>>& all() const { return fields_; }
  const Field<C>* find(const std::string& name) const {
    for (const Field<C>& f : fields_)
      if (f.name == name) return &f;
    return nullptr;
  }
  /// Throws std::invalid_argument naming the first field out of its range (or not an integer
  /// where one is needed): "name = value (allowed: range)".
  void validate(const C& c) const {
    for (const Field<C>& f : fields_) {
      const double v = f.get(c);
      if (!f.range.contains(v))
        throw std::invalid_argument(f.name + " = " + formatValue(f.kind, v) +
                                    " (allowed: " + f.range.text() + ")");
    }
  }

 private:
  Fields& push(std::string name, Kind kind, Range range, std::string doc,
               std::function<double(const C&)> get, std::function<void(C&, double)> set) {
    if (find(name)) throw std::logic_error("config field declared twice: " + name);
    fields_.push_back(
        {std::move(name), kind, range, std::move(doc), std::move(get), std::move(set)});
    return *this;
  }
  std::vector<Field<C>> fields_;
};

/// One row of a node's parameter table: a config field's, or a parameter the node reads itself
/// (frames, files, lists).
struct ParameterDoc {
  std::string name;
  std::string type;  // int, double, bool, string, list
  std::string default_value;
  std::string range;  // empty: any
  std::string doc;
  bool in_config = false;  // a config field's (loaded with its table), not the node's own
};

/// The rows of a config table, with each field's default from `defaults`.
template <class C>
std::vector<ParameterDoc> describe(const Fields<C>& fields, const C& defaults) {
  std::vector<ParameterDoc> rows;
  for (const Field<C>& f : fields.all()) {
    const char* type = f.kind == Kind::kInt ? "int" : f.kind == Kind::kBool ? "bool" : "double";
    rows.push_back({f.name, type, formatValue(f.kind, f.get(defaults)),
                    f.kind == Kind::kBool ? "" : f.range.text(), f.doc, true});
  }
  return rows;
}

/// A markdown table of the rows (name, type, default, range, doc), one line a parameter.
std::string markdownTable(const std::vector<ParameterDoc>& rows);

}  // namespace adaptive_perception::config
