#pragma once
// Bad input is refused with a message that names it (DESIGN: "validate() names the field"): the
// check the config and constructor tests share.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace adaptive_perception::test_support {

/// The message of the exception E (std::invalid_argument unless given) that `f()` throws, or
/// "accepted" when it throws none.
template <class E = std::invalid_argument, class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "accepted";
}

/// Passes when `f()` throws std::invalid_argument with a message that contains `name`; a failure
/// shows the message, or that nothing was thrown.
template <class F>
::testing::AssertionResult refusedNaming(F&& f, const std::string& name) {
  const std::string message = refusal(f);
  if (message != "accepted" && message.find(name) != std::string::npos)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "expected a refusal naming '" << name << "', got: " << message;
}

}  // namespace adaptive_perception::test_support
