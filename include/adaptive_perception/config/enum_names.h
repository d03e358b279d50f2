#pragma once
// An option that takes one of a few words (a filter variant, a lighting script, a colour space):
// its words written once, in one table, from which come the parse function with the error that
// lists the allowed words, the name of a value and the list of names, so that the three cannot
// drift apart.
//
//   const config::EnumNames<Variant>& variants() {
//     static const config::EnumNames<Variant> names(
//         "variant", {{Variant::kStandard, "standard"}, {Variant::kAnchor, "anchor"}});
//     return names;
//   }
//   Variant parseVariant(const std::string& s) { return variants().parse(s); }
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace adaptive_perception::config {

template <class E>
class EnumNames {
 public:
  /// `what` names the option in errors; `names` gives each value its one name (the first of a
  /// value counts when a value is listed twice); `aliases` are more words that parse to a value
  /// but are never printed as its name (old spellings).
  EnumNames(std::string what, std::vector<std::pair<E, std::string>> names,
            std::vector<std::pair<E, std::string>> aliases = {})
      : what_(std::move(what)), names_(std::move(names)), aliases_(std::move(aliases)) {
    if (names_.empty()) throw std::logic_error("EnumNames for " + what_ + ": no names");
  }

  /// The value named `word` (a name or an alias); throws std::invalid_argument
  /// "what = 'word' (allowed: a, b, c)" otherwise.
  E parse(const std::string& word) const {
    for (const auto* list : {&names_, &aliases_})
      for (const auto& [value, name] : *list)
        if (name == word) return value;
    throw std::invalid_argument(what_ + " = '" + word + "' (allowed: " + allowed() + ")");
  }
  /// The name of `value`; throws std::logic_error for a value the table lacks (a table that was
  /// not updated with its enumeration).
  const std::string& name(E value) const {
    for (const auto& [v, name] : names_)
      if (v == value) return name;
    throw std::logic_error("EnumNames for " + what_ + ": a value without a name");
  }
  /// Every name, in the table's order (aliases aside).
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& entry : names_) out.push_back(entry.second);
    return out;
  }
  /// The names, comma-separated: "a, b, c" (aliases are taken, not offered).
  std::string allowed() const {
    std::string out;
    for (const auto& entry : names_) out += (out.empty() ? "" : ", ") + entry.second;
    return out;
  }

 private:
  std::string what_;
  std::vector<std::pair<E, std::string>> names_, aliases_;
};

}  // namespace adaptive_perception::config
