#include "command_line.h"

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <iostream>

namespace adaptive_perception::tools {

namespace {

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

/// Refuses a value that is not a number of `kind` in `range`, naming it.
CLI::Validator fieldCheck(config::Kind kind, config::Range range) {
  return CLI::Validator(
      [kind, range](std::string& s) -> std::string {
        try {
          const double v = CommandLine::parseNumber(kind, s);
          if (!range.contains(v))
            return config::formatValue(kind, v) + " is out of range " + range.text();
        } catch (const std::invalid_argument& e) {
          return e.what();
        }
        return "";
      },
      kind == config::Kind::kBool ? "" : "in " + range.text());
}

}  // namespace

CommandLine::Option* CommandLine::Option::required() {
  option_->required();
  return this;
}

CommandLine::Option* CommandLine::Option::oneOf(const std::vector<std::string>& words) {
  option_->check(CLI::IsMember(words));
  return this;
}

CommandLine::Option* CommandLine::Option::existingFile() {
  option_->check(CLI::ExistingFile);
  return this;
}

CommandLine::Option* CommandLine::Option::inRange(config::Range range) {
  option_->check(fieldCheck(config::Kind::kDouble, range));
  return this;
}

CommandLine::Option* CommandLine::Option::group(const std::string& name) {
  option_->group(name);
  return this;
}

std::size_t CommandLine::Option::count() const { return option_->count(); }

CommandLine::CommandLine(const std::string& name, const std::string& description)
    : app_(std::make_unique<CLI::App>(description, name)) {
  app_->option_defaults()->always_capture_default();
  app_->formatter(std::make_shared<HelpFormatter>());
  app_->get_formatter()->column_width(36);
}

CommandLine::~CommandLine() = default;

CommandLine::Option* CommandLine::keep(CLI::Option* option) {
  options_.push_back(std::make_unique<Option>(option));
  return options_.back().get();
}

#define AP_TYPED_OPTION(T)                                                                     \
  CommandLine::Option* CommandLine::option(const std::string& name, T* value,                 \
                                           const std::string& doc) {                          \
    return keep(app_->add_option("--" + name, *value, doc));                                   \
  }
AP_TYPED_OPTION(int)
AP_TYPED_OPTION(long)
AP_TYPED_OPTION(long long)
AP_TYPED_OPTION(unsigned)
AP_TYPED_OPTION(unsigned long)
AP_TYPED_OPTION(double)
AP_TYPED_OPTION(float)
AP_TYPED_OPTION(std::string)
AP_TYPED_OPTION(std::vector<std::string>)
AP_TYPED_OPTION(std::vector<double>)
#undef AP_TYPED_OPTION

CommandLine::Option* CommandLine::flag(const std::string& name, bool* value,
                                       const std::string& doc) {
  return keep(app_->add_flag("--" + name, *value, doc));
}

CommandLine::Option* CommandLine::wordOption(const std::string& name,
                                             std::function<void(const std::string&)> set,
                                             std::function<std::string(const std::string&)> check,
                                             const std::string& allowed,
                                             const std::string& default_word,
                                             const std::string& doc) {
  return keep(app_->add_option_function<std::string>("--" + name, std::move(set), doc)
                  ->check(CLI::Validator(
                      [check = std::move(check)](std::string& s) { return check(s); }, allowed))
                  ->default_str(default_word));
}

void CommandLine::fieldOption(const std::string& name, config::Kind kind, config::Range range,
                              const std::string& default_text, const std::string& doc) {
  app_->add_option_function<std::string>(
          "--" + name,
          [this, name, kind](const std::string& s) {
            try {
              for (const auto& set : field_setters_.at(name)) set(parseNumber(kind, s));
            } catch (const std::invalid_argument& e) {  // checked before: not expected
              throw CLI::ValidationError("--" + name, e.what());
            }
          },
          doc)
      ->default_str(default_text)
      ->type_name(kind == config::Kind::kInt    ? "INT"
                  : kind == config::Kind::kBool ? "BOOL"
                                                : "FLOAT")
      ->check(fieldCheck(kind, range));
}

const std::string& CommandLine::inputBag(const std::string& doc) {
  option("bag", &input_bag_, doc)->required()->existingFile();
  return input_bag_;
}

const std::string& CommandLine::resultsFolder(const std::string& what) {
  results_folder_ = "results/" + app_->get_name();
  option("output", &results_folder_, "folder for " + what);
  return results_folder_;
}

const double& CommandLine::measurementSeconds(double default_s) {
  measurement_s_ = default_s;
  option("seconds", &measurement_s_, config::aboveZero(3600), "time per measurement, s");
  return measurement_s_;
}

const bool& CommandLine::overwrite(const std::string& what) {
  flag("overwrite", &overwrite_, "replace " + what + " if it exists");
  return overwrite_;
}

const std::string& CommandLine::outputFile(const std::string& doc, const std::string& what) {
  option("output", &output_file_, doc)->required();
  overwrite(what);
  return output_file_;
}

void CommandLine::refuseExisting(const std::string& path) const {
  std::error_code ec;
  if (!overwrite_ && std::filesystem::exists(path, ec))
    fail("'" + path + "' exists; pass --overwrite to replace it");
}

void CommandLine::parse(int argc, char** argv) {
  app_->allow_extras();
  try {
    app_->parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app_->help();
    std::exit(0);
  } catch (const CLI::ParseError& e) {
    failOnExtras();
    fail(e.what());
  }
  failOnExtras();
  if (!output_file_.empty()) refuseExisting(output_file_);
}

void CommandLine::fail(const std::string& msg) const {
  std::cerr << app_->get_name() << ": error: " << msg << "\nRun with --help for the options.\n";
  std::exit(2);
}

std::string CommandLine::name() const { return app_->get_name(); }

std::string CommandLine::help() const { return app_->help(); }

double CommandLine::parseNumber(config::Kind kind, const std::string& s) {
  if (kind == config::Kind::kBool) {
    if (s == "1" || s == "true") return 1.0;
    if (s == "0" || s == "false") return 0.0;
    throw std::invalid_argument("expects 0, 1, true or false, got '" + s + "'");
  }
  char* end = nullptr;
  const double v = kind == config::Kind::kInt
                       ? static_cast<double>(std::strtoll(s.c_str(), &end, 10))
                       : std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0')
    throw std::invalid_argument(std::string("expects ") +
                                (kind == config::Kind::kInt ? "an integer" : "a number") +
                                ", got '" + s + "'");
  return v;
}

void CommandLine::failOnExtras() const {
  const std::vector<std::string> extras = app_->remaining();
  if (extras.empty()) return;
  std::string words;
  for (const std::string& w : extras) words += " " + w;
  fail("not options of this tool:" + words);
}

}  // namespace adaptive_perception::tools
