#include "detector/forward_fault.hpp"

#include <cstdlib>
#include <string_view>

#include "common/checked_number.hpp"
#include "common/input_error.hpp"

namespace rtmot::detector {
namespace {

constexpr const char* kVariable = "RTMOT_FAULT_FORWARD_AFTER";

}  // namespace

ForwardFault::ForwardFault() {
  const char* text = std::getenv(kVariable);
  if (text == nullptr) return;
  const auto value = parse_integer(std::string_view(text), {0, 1'000'000'000'000});
  if (!value) {
    throw InputError(kVariable, 0, "",
                     std::string("expected a count of forward passes, got '") + text + "'",
                     ExitCode::usage);
  }
  after_ = *value;
}

bool ForwardFault::fails_now() {
  return after_ >= 0 && passes_++ >= after_;
}

std::string ForwardFault::what() const {
  return "injected by " + std::string(kVariable) + "=" + std::to_string(after_) +
         ": the forward pass fails as a lost GPU's would";
}

}  // namespace rtmot::detector
