#pragma once
// The tools' command lines, on CLI11 (Debian's libcli11-dev), which only command_line.cpp
// includes: it is header-only, and it took 10 s of compiling in every tool. Each option is
// declared with the variable it sets (whose value before parsing is the default), a one-line doc
// that states the unit, and where it matters its allowed range; a config's field table
// (config/fields.h) adds one option per field with the field's name, range and doc, as the node's
// ROS parameter of the same name. Then:
//   - `--help` lists every option with its type, range and default, and exits 0;
//   - an unknown option, a stray word, a value that is not a number where one is needed, or one out
//     of range is refused with a message naming it, and the tool exits 2.
// Options are written `--name value` or `--name=value`; a flag takes no value, so a word after it
// is refused, never swallowed.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "adaptive_perception/config/enum_names.h"
#include "adaptive_perception/config/fields.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace adaptive_perception::tools {

class CommandLine {
 public:
  /// One option, as declared; its setters return it, so that they chain (`->required()`).
  class Option {
   public:
    explicit Option(CLI::Option* option) : option_(option) {}
    /// The tool refuses to run without it.
    Option* required();
    /// Its value must be one of `words`; any other is refused naming them.
    Option* oneOf(const std::vector<std::string>& words);
    /// Its value must name an existing file.
    Option* existingFile();
    /// Its number must lie in `range`.
    Option* inRange(config::Range range);
    /// Listed under `name` in --help.
    Option* group(const std::string& name);
    /// How often it was given (after parse()).
    std::size_t count() const;

   private:
    CLI::Option* option_;
  };

  /// `description`: what the tool does, first in --help.
  CommandLine(const std::string& name, const std::string& description);
  ~CommandLine();
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  /// `--name VALUE` into *value; its value now is the default --help shows.
  Option* option(const std::string& name, int* value, const std::string& doc);
  Option* option(const std::string& name, long* value, const std::string& doc);
  Option* option(const std::string& name, long long* value, const std::string& doc);
  Option* option(const std::string& name, unsigned* value, const std::string& doc);
  Option* option(const std::string& name, unsigned long* value, const std::string& doc);
  Option* option(const std::string& name, double* value, const std::string& doc);
  Option* option(const std::string& name, float* value, const std::string& doc);
  Option* option(const std::string& name, std::string* value, const std::string& doc);
  Option* option(const std::string& name, std::vector<std::string>* value,
                 const std::string& doc);
  Option* option(const std::string& name, std::vector<double>* value, const std::string& doc);
  /// A number checked against `range` (config::Range: open or closed ends).
  template <class T>
  Option* option(const std::string& name, T* value, config::Range range, const std::string& doc) {
    return option(name, value, doc)->inRange(range);
  }
  /// --name, one of the words of `words` (config/enum_names.h), into *value, whose value now is the
  /// default; --help lists the words, and any other word is refused naming them.
  template <class E>
  Option* word(const std::string& name, E* value, const config::EnumNames<E>& words,
               const std::string& doc) {
    return wordOption(
        name, [value, &words](const std::string& s) { *value = words.parse(s); },
        [&words](const std::string& s) -> std::string {
          try {
            words.parse(s);
          } catch (const std::invalid_argument& e) {
            return e.what();
          }
          return "";
        },
        "one of " + words.allowed(), words.name(*value), doc);
  }
  /// `--name` alone sets *value to true (default false).
  Option* flag(const std::string& name, bool* value, const std::string& doc);
  /// --bag, the bag the tool reads: required, and refused at parse() (exit 2, naming it) when no
  /// such file exists. The reference holds the parsed value after parse().
  const std::string& inputBag(const std::string& doc);
  /// --output, the folder of the tool's results: results/<tool name> by default (relative to the
  /// working directory); `what` names what goes in it. The reference holds the parsed value after
  /// parse().
  const std::string& resultsFolder(const std::string& what);
  /// --seconds, a benchmark's wall-clock time per measurement (bench_timing.h), with the tool's
  /// default. The reference holds the parsed value after parse().
  const double& measurementSeconds(double default_s);
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
  const bool& overwrite(const std::string& what);
  /// --output, the one file the tool writes (`doc` says what it is), required, and --overwrite
  /// (`what` as for overwrite()): parse() refuses the file where it exists and --overwrite was not
  /// given, before any work. The reference holds the parsed value after parse().
  const std::string& outputFile(const std::string& doc, const std::string& what);
  /// Whether --overwrite was given (after parse()).
  bool overwriteGiven() const { return overwrite_; }
  /// Nothing the user has is replaced unasked: exits 2 naming `path` when it exists and
  /// --overwrite was not given.
  void refuseExisting(const std::string& path) const;
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
      if (setters.size() == 1)
        fieldOption(f.name, f.kind, f.range, config::formatValue(f.kind, f.get(*c)), f.doc);
    }
  }
  /// Parses; on --help prints the options and exits 0, on an error prints it and exits 2. Words
  /// that are not options of the tool are named first (a mistyped option would otherwise show as
  /// a missing one).
  void parse(int argc, char** argv);
  /// A check the options cannot express (two options that exclude each other, a file that
  /// exists): prints `error: msg` and exits 2.
  [[noreturn]] void fail(const std::string& msg) const;
  /// The tool's name, and its --help text.
  std::string name() const;
  std::string help() const;

  /// The value of `s` as a field of `kind` reads it (an integer, a boolean 0 | 1 | true | false,
  /// a real); throws std::invalid_argument naming the text otherwise.
  static double parseNumber(config::Kind kind, const std::string& s);

 private:
  Option* wordOption(const std::string& name, std::function<void(const std::string&)> set,
                     std::function<std::string(const std::string&)> check,
                     const std::string& allowed, const std::string& default_word,
                     const std::string& doc);
  void fieldOption(const std::string& name, config::Kind kind, config::Range range,
                   const std::string& default_text, const std::string& doc);
  Option* keep(CLI::Option* option);
  void failOnExtras() const;

  std::unique_ptr<CLI::App> app_;
  std::vector<std::unique_ptr<Option>> options_;
  std::string input_bag_, results_folder_, output_file_;
  double measurement_s_ = 1.0;
  std::uint64_t seed_ = 1;
  bool overwrite_ = false;
  std::map<std::string, std::vector<std::function<void(double)>>> field_setters_;
};

}  // namespace adaptive_perception::tools
