// `rtmot model check MODEL`: what a detector model holds and which engines run it, before a run
// depends on it (detector/model_check.hpp). Exits 0 when `rtmot run` can use the model, 4
// (bad_model) with every problem named when it cannot.
#include <fmt/format.h>

#include <memory>
#include <string>

#include "apps/subcommand.hpp"
#include "common/exit_codes.hpp"
#include "detector/model_check.hpp"

namespace rtmot::app {
namespace {

struct ModelCheckOptions {
  std::string model;
  std::string anchors;
};

int run_model_check(const ModelCheckOptions& options) {
  const detector::ModelCheck check = detector::check_model({options.model, options.anchors});
  fmt::print("{}", detector::format_model_check(check));
  return check.usable() ? 0 : to_int(ExitCode::bad_model);
}

}  // namespace

Subcommand add_model_command(CLI::App& parent) {
  auto options = std::make_shared<ModelCheckOptions>();
  CLI::App* cli = parent.add_subcommand("model", "Inspect detector models");
  cli->require_subcommand(1);
  CLI::App* check = cli->add_subcommand(
      "check",
      "Check a model against the detector's contract (docs/model.md): its outputs, anchors, "
      "classes, checksums, and which engines of this build run it; exit 4 naming each problem");
  check->add_option("model", options->model, "the ONNX file")->required();
  check->add_option("--anchors", options->anchors,
                    "the anchors CSV (default: the model's name with .anchors.csv)");
  return {cli, [options] { return run_model_check(*options); }, /*stops_on_signals=*/false};
}

}  // namespace rtmot::app
