#pragma once
// Command-line options from a config's field table (config/fields.h): every field is the option
// --<name> of the same name as its ROS parameter, checked against the same range.
#include <string>

#include "adaptive_perception/config/fields.h"
#include "tool_args.h"

namespace adaptive_perception::tools {

/// Sets every field given on the command line; a value out of range, or not a number (an integer,
/// a boolean: 0 | 1 | true | false), fails with the option, the value and the range named.
template <class C>
void applyFields(Args& args, const config::Fields<C>& fields, C* c) {
  for (const config::Field<C>& f : fields.all()) {
    if (!args.has(f.name)) continue;
    double v = 0.0;
    if (f.kind == config::Kind::kBool) {
      const std::string s = args.get(f.name, "");
      if (s == "1" || s == "true")
        v = 1.0;
      else if (s != "0" && s != "false")
        args.fail("--" + f.name + " expects 0, 1, true or false, got '" + s + "'");
    } else if (f.kind == config::Kind::kInt) {
      v = static_cast<double>(args.getInt(f.name, 0));
    } else {
      v = args.getDouble(f.name, 0.0);
    }
    if (!f.range.contains(v))
      args.fail("--" + f.name + " = " + config::formatValue(f.kind, v) + " is out of range " +
                f.range.text());
    f.set(*c, v);
  }
}

/// The options of a table for --help: one line each, with the default (from `defaults`), the range
/// and the doc.
template <class C>
std::string fieldsHelp(const config::Fields<C>& fields, const C& defaults) {
  std::string out;
  for (const config::Field<C>& f : fields.all())
    out += "  --" + f.name + " (" + config::formatValue(f.kind, f.get(defaults)) +
           (f.kind == config::Kind::kBool ? "" : ", " + f.range.text()) + "): " + f.doc + "\n";
  return out;
}

}  // namespace adaptive_perception::tools
