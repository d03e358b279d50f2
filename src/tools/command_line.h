#pragma once
// The tools' command lines, on CLI11 (Debian's libcli11-dev). Each option is declared with the
// variable it sets (whose value before parsing is the default), a one-line doc that states the
// unit, and where it matters its allowed range; a config's field table (config/fields.h) adds one
// option per field with the field's name, range and doc, as the node's ROS parameter of the same
// name. Then:
//   - `--help` lists every option with its type, range and default, and exits 0;
//   - an unknown option, a stray word, a value that is not a number where one is needed, or one out
//     of range is refused with a message naming it, and the tool exits 2.
// Options are written `--name value` or `--name=value`; a flag takes no value, so a word after it
// is refused, never swallowed.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "adaptive_perception/config/enum_names.h"
#include "adaptive_perception/config/fields.h"

namespace adaptive_perception::tools {

/// --help as the tools print it: `--name TYPE:range` and then the doc ending in `(default: X)`.
class HelpFormatter : public CLI::Formatter {
 public:
  std::string make_option_opts(const CLI::Option* opt) const override {
    std::string out;
    if (opt->get_type_size() != 0) {
      if (!opt->get_type_name().empty()) out += " " + opt->get_type_name();
      if (opt->get_required()) out += " REQUIRED";
    }
    return out;
  }
  std::string make_option_desc(const CLI::Option* opt) const override {
    const std::string& def = opt->get_default_str();
    if (opt->get_type_size() == 0 || def.empty()) return opt->get_description();
    return opt->get_description() + " (default: " + def + ")";
  }
};

class CommandLine {
 public:
  /// `description`: what the tool does, first in --help.
  CommandLine(const std::string& name, const std::string& description) : app_(description, name) {
    app_.option_defaults()->always_capture_default();
    app_.formatter(std::make_shared<HelpFormatter>());
    app_.get_formatter()->column_width(36);
  }
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  /// `--name VALUE` into *value; its value now is the default --help shows.
  template <class T>
  CLI::Option* option(const std::string& name, T* value, const std::string& doc) {
    return app_.add_option("--" + name, *value, doc);
  }
  /// A number checked against `range` (config::Range: open or closed ends).
  template <class T>
  CLI::Option* option(const std::string& name, T* value, config::Range range,
                      const std::string& doc) {
    return option(name, value, doc)->check(rangeCheck(range));
  }
  /// --name, one of the words of `words` (config/enum_names.h), into *value, whose value now is the
  /// default; --help lists the words, and any other word is refused naming them.
  template <class E>
  CLI::Option* word(const std::string& name, E* value, const config::EnumNames<E>& words,
                    const std::string& doc) {
    return app_
        .add_option_function<std::string>(
            "--" + name, [value, &words](const std::string& s) { *value = words.parse(s); }, doc)
        ->check(CLI::Validator(
            [&words](std::string& s) -> std::string {
              try {
                words.parse(s);
              } catch (const std::invalid_argument& e) {
                return e.what();
              }
              return "";
            },
            "one of " + words.allowed()))
        ->default_str(words.name(*value));
  }
  /// `--name` alone sets *value to true (default false).
  CLI::Option* flag(const std::string& name, bool* value, const std::string& doc) {
    return app_.add_flag("--" + name, *value, doc);
  }
  /// --bag, the bag the tool reads: required, and refused at parse() (exit 2, naming it) when no
  /// such file exists. The reference holds the parsed value after parse().
  const std::string& inputBag(const std::string& doc) {
    option("bag", &input_bag_, doc)->required()->check(CLI::ExistingFile);
    return input_bag_;
  }
  /// --output, the folder of the tool's results: results/<tool name> by default (relative to the
  /// working directory); `what` names what goes in it. The reference holds the parsed value after
  /// parse().
  const std::string& resultsFolder(const std::string& what) {
    results_folder_ = "results/" + app_.get_name();
    option("output", &results_folder_, "folder for " + what);
    return results_folder_;
  }
  /// --seconds, a benchmark's wall-clock time per measurement (bench_timing.h), with the tool's
  /// default. The reference holds the parsed value after parse().
  const double& measurementSeconds(double default_s) {
    measurement_s_ = default_s;
    option("seconds", &measurement_s_, config::aboveZero(3600), "time per measurement, s");
    return measurement_s_;
  }
  /// --seed, the random seed: the same seed repeats a run exactly. Default 1; the reference holds
  /// the parsed value after parse().
  const std::uint64_t& seed() {
    seed(&seed_);
    return seed_;
  }
  /// --seed into a config's own seed field (its value now is the default).
  template <class T>
  void seed(T* value) {
    option("seed", value, "random seed: the same seed repeats a run exactly");
  }
  /// --overwrite: the tool may replace `what` (as --help names it) where it exists already; the
  /// reference holds the parsed value after parse().
  const bool& overwrite(const std::string& what) {
    flag("overwrite", &overwrite_, "replace " + what + " if it exists");
    return overwrite_;
  }
  /// --output, the one file the tool writes (`doc` says what it is), required, and --overwrite
  /// (`what` as for overwrite()): parse() refuses the file where it exists and --overwrite was not
  /// given, before any work. The reference holds the parsed value after parse().
  const std::string& outputFile(const std::string& doc, const std::string& what) {
    option("output", &output_file_, doc)->required();
    overwrite(what);
    return output_file_;
  }
  /// Whether --overwrite was given (after parse()).
  bool overwriteGiven() const { return overwrite_; }
  /// Nothing the user has is replaced unasked: exits 2 naming `path` when it exists and
  /// --overwrite was not given.
  void refuseExisting(const std::string& path) const {
    std::error_code ec;
    if (!overwrite_ && std::filesystem::exists(path, ec))
      fail("'" + path + "' exists; pass --overwrite to replace it");
  }
  /// One option per field of a config's table (or of those named in `only`): --<field name> with
  /// the field's default (read from *c now), range and doc. A name shared by two tables sets the
  /// field in both.
  template <class C>
  void fields(const config::Fields<C>& table, C* c, const std::vector<std::string>& only = {}) {
    for (const std::string& name : only)
      if (!table.find(name)) throw std::logic_error("no config field named " + name);
    for (const config::Field<C>& f : table.all()) {
      if (!only.empty() && std::find(only.begin(), only.end(), f.name) == only.end()) continue;
      auto& setters = field_setters_[f.name];
      setters.push_back([c, set = f.set](double v) { set(*c, v); });
      if (setters.size() > 1) continue;
      const std::string name = f.name;
      const config::Kind kind = f.kind;
      app_.add_option_function<std::string>(
              "--" + name,
              [this, name, kind](const std::string& s) {
                for (const auto& set : field_setters_.at(name)) set(parseNumber(kind, s));
              },
              f.doc)
          ->default_str(config::formatValue(kind, f.get(*c)))
          ->type_name(kind == config::Kind::kInt    ? "INT"
                      : kind == config::Kind::kBool ? "BOOL"
                                                    : "FLOAT")
          ->check(fieldCheck(kind, f.range));
    }
  }
  /// Parses; on --help prints the options and exits 0, on an error prints it and exits 2. Words
  /// that are not options of the tool are named first (a mistyped option would otherwise show as
  /// a missing one).
  void parse(int argc, char** argv) {
    app_.allow_extras();
    try {
      app_.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
      std::cout << app_.help();
      std::exit(0);
    } catch (const CLI::ParseError& e) {
      failOnExtras();
      fail(e.what());
    }
    failOnExtras();
    if (!output_file_.empty()) refuseExisting(output_file_);
  }
  /// A check the options cannot express (two options that exclude each other, a file that
  /// exists): prints `error: msg` and exits 2.
  [[noreturn]] void fail(const std::string& msg) const {
    std::cerr << app_.get_name() << ": error: " << msg << "\nRun with --help for the options.\n";
    std::exit(2);
  }
  CLI::App& app() { return app_; }

  /// The value of `s` as a field of `kind` reads it (an integer, a boolean 0 | 1 | true | false,
  /// a real); throws CLI::ValidationError naming the text otherwise.
  static double parseNumber(config::Kind kind, const std::string& s) {
    if (kind == config::Kind::kBool) {
      if (s == "1" || s == "true") return 1.0;
      if (s == "0" || s == "false") return 0.0;
      throw CLI::ValidationError("expects 0, 1, true or false, got '" + s + "'");
    }
    char* end = nullptr;
    const double v = kind == config::Kind::kInt
                         ? static_cast<double>(std::strtoll(s.c_str(), &end, 10))
                         : std::strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0')
      throw CLI::ValidationError(std::string("expects ") +
                                 (kind == config::Kind::kInt ? "an integer" : "a number") +
                                 ", got '" + s + "'");
    return v;
  }

 private:
  void failOnExtras() const {
    const std::vector<std::string> extras = app_.remaining();
    if (extras.empty()) return;
    std::string words;
    for (const std::string& w : extras) words += " " + w;
    fail("not options of this tool:" + words);
  }
  static CLI::Validator fieldCheck(config::Kind kind, config::Range range) {
    return CLI::Validator(
        [kind, range](std::string& s) -> std::string {
          try {
            const double v = parseNumber(kind, s);
            if (!range.contains(v))
              return config::formatValue(kind, v) + " is out of range " + range.text();
          } catch (const CLI::ValidationError& e) {
            return e.what();
          }
          return "";
        },
        kind == config::Kind::kBool ? "" : "in " + range.text());
  }
  static CLI::Validator rangeCheck(config::Range range) {
    return fieldCheck(config::Kind::kDouble, range);
  }

  CLI::App app_;
  std::string input_bag_, results_folder_, output_file_;
  double measurement_s_ = 1.0;
  std::uint64_t seed_ = 1;
  bool overwrite_ = false;
  std::map<std::string, std::vector<std::function<void(double)>>> field_setters_;
};

}  // namespace adaptive_perception::tools
