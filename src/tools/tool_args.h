#pragma once
// Minimal `--key value` / `--flag` command-line parsing shared by the command-line tools. Unknown
// or malformed options print the usage line and exit with status 2.
#include <cstdlib>
#include <iostream>
#include <map>
#include <set>
#include <string>

namespace adaptive_perception::tools {

class Args {
 public:
  /// `help`, when given, is printed after the usage line on --help only (the options in full).
  Args(int argc, char** argv, std::string usage, const std::string& help = "")
      : usage_(std::move(usage)) {
    for (int i = 1; i < argc; ++i) {
      std::string a = argv[i];
      if (a == "-h" || a == "--help") {
        std::cout << "usage: " << usage_ << "\n" << help;
        std::exit(0);
      }
      if (a.rfind("--", 0) != 0) fail("unexpected argument '" + a + "'");
      a = a.substr(2);
      const auto eq = a.find('=');
      if (eq != std::string::npos) {
        values_[a.substr(0, eq)] = a.substr(eq + 1);
      } else if (i + 1 < argc && std::string(argv[i + 1]).rfind("--", 0) != 0) {
        values_[a] = argv[++i];
      } else {
        values_[a] = "";  // a flag
      }
    }
  }

  std::string get(const std::string& key, const std::string& def) {
    used_.insert(key);
    auto it = values_.find(key);
    return it == values_.end() ? def : it->second;
  }
  bool has(const std::string& key) {
    used_.insert(key);
    return values_.count(key) > 0;
  }
  double getDouble(const std::string& key, double def) {
    const std::string s = get(key, "");
    if (s.empty()) return def;
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (*end != '\0') fail("--" + key + " expects a number, got '" + s + "'");
    return v;
  }
  long long getInt(const std::string& key, long long def) {
    const std::string s = get(key, "");
    if (s.empty()) return def;
    char* end = nullptr;
    const long long v = std::strtoll(s.c_str(), &end, 10);
    if (*end != '\0') fail("--" + key + " expects an integer, got '" + s + "'");
    return v;
  }
  /// Call after reading every option: rejects options the tool does not know.
  void finish() {
    for (const auto& kv : values_)
      if (!used_.count(kv.first)) fail("unknown option --" + kv.first);
  }
  [[noreturn]] void fail(const std::string& msg) const {
    std::cerr << "error: " << msg << "\nusage: " << usage_ << "\n";
    std::exit(2);
  }

 private:
  std::string usage_;
  std::map<std::string, std::string> values_;
  std::set<std::string> used_;
};

}  // namespace adaptive_perception::tools
