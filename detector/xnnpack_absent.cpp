// Built instead of xnnpack_network.cpp where XNNPACK or ONNX is missing: the backend is refused
// with the way to get it (choose_backend refuses it first; this is the last guard).
#include <stdexcept>

#include "common/input_error.hpp"
#include "detector/xnnpack_network.hpp"

namespace rtmot::detector {

bool xnnpack_built() {
  return false;
}

bool xnnpack_runs_here() {
  return false;
}

const char* xnnpack_supported_operators() {
  return "none (this build has no XNNPACK)";
}

struct XnnpackNetwork::Impl {};

XnnpackNetwork::XnnpackNetwork(const XnnpackNetworkConfig& /*config*/) {
  throw InputError("detector", 0, "backend",
                   "this build has no XNNPACK backend (install libxnnpack-dev and libonnx-dev, "
                   "scripts/install_deps.sh, and rebuild)",
                   ExitCode::usage);
}
XnnpackNetwork::~XnnpackNetwork() = default;
float* XnnpackNetwork::input(int /*slot*/) {
  throw std::logic_error("no XNNPACK");
}
void XnnpackNetwork::run(int /*count*/) {
  throw std::logic_error("no XNNPACK");
}
const float* XnnpackNetwork::boxes() const {
  throw std::logic_error("no XNNPACK");
}
const float* XnnpackNetwork::logits() const {
  throw std::logic_error("no XNNPACK");
}
std::size_t XnnpackNetwork::anchors() const {
  return 0;
}
std::size_t XnnpackNetwork::classes() const {
  return 0;
}
std::string XnnpackNetwork::summary() const {
  return {};
}
std::string XnnpackNetwork::pool_use() const {
  return {};
}
ActivationRanges XnnpackNetwork::recorded_ranges() const {
  return {};
}
void XnnpackNetwork::clear_recorded_ranges() {}

}  // namespace rtmot::detector
