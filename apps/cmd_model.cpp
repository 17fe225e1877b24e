// `rtmot model check MODEL`: what a detector model holds and which engines run it, before a run
// depends on it (detector/model_check.hpp). Exits 0 when `rtmot run` can use the model, 4
// (bad_model) with every problem named when it cannot.
// `rtmot model calibrate MODEL VIDEO --out FILE`: the int8 engine's activation ranges measured on
// sample frames of a video (detector/int8_calibration.hpp; scripts/calibrate_int8.sh).
#include <fmt/format.h>

#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "apps/subcommand.hpp"
#include "common/exit_codes.hpp"
#include "common/input_error.hpp"
#include "detector/int8_calibration.hpp"
#include "detector/model_check.hpp"
#include "platform/video_source.hpp"

namespace rtmot::app {
namespace {

struct ModelCheckOptions {
  std::string model;
  std::string anchors;
  std::string int8_ranges;
};

struct CalibrateOptions {
  std::string model;
  std::string video;
  std::string out;
  int first{detector::kCalibrationFirstFrame};
  int step{detector::kCalibrationFrameStep};
  int count{detector::kCalibrationFrames};
};

int run_model_calibrate(const CalibrateOptions& options) {
  std::set<int> wanted;
  for (int i = 0; i < options.count; ++i) wanted.insert(options.first + i * options.step);
  const auto source = platform::open_video_source(options.video);
  std::vector<cv::Mat> frames;
  cv::Mat image;
  platform::FrameInfo info;
  for (int number = 1; number <= *wanted.rbegin(); ++number) {
    if (source->read(image, info) != platform::ReadStatus::frame) {
      throw InputError(options.video, 0, "",
                       "ended before frame " + std::to_string(number) + " of the " +
                           std::to_string(options.count) + " sample frames asked",
                       ExitCode::bad_input);
    }
    if (wanted.count(number) != 0) frames.push_back(image.clone());
  }
  detector::SsdConfig config;
  config.model_path = options.model;
  const detector::ActivationRanges ranges = detector::calibrate_activation_ranges(config, frames);
  std::ofstream out(options.out, std::ios::binary | std::ios::trunc);
  out << detector::activation_ranges_text(ranges);
  out.close();
  if (!out) {
    throw InputError(options.out, 0, "", "cannot write the ranges", ExitCode::io_error);
  }
  fmt::print("{}: {} tensors' ranges over {} frames of {} (model sha256 {})\n", options.out,
             ranges.tensors.size(), ranges.frames, options.video, ranges.model_sha256);
  return 0;
}

int run_model_check(const ModelCheckOptions& options) {
  const detector::ModelCheck check =
      detector::check_model({options.model, options.anchors, options.int8_ranges});
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
  check->add_option("--ranges", options->int8_ranges,
                    "the int8 engine's activation ranges (default: configs/int8/<model "
                    "name>.ranges, as backend xnnpack-int8 reads them)");
  auto calibration = std::make_shared<CalibrateOptions>();
  CLI::App* calibrate = cli->add_subcommand(
      "calibrate",
      "Measure the int8 engine's activation ranges (backend xnnpack-int8): the model in fp32 on "
      "XNNPACK over sample frames of a video, each tensor's min and max written to --out "
      "(docs/cpu-detector.md)");
  calibrate->add_option("model", calibration->model, "the ONNX file")->required();
  calibrate->add_option("video", calibration->video, "the sample video's URI (file://...)")
      ->required();
  calibrate->add_option("--out", calibration->out, "the ranges file to write")->required();
  calibrate->add_option("--first", calibration->first, "the first sample frame (1-based)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1 << 20));
  calibrate->add_option("--step", calibration->step, "frames between samples")
      ->capture_default_str()
      ->check(CLI::Range(1, 1 << 20));
  calibrate->add_option("--count", calibration->count, "how many sample frames")
      ->capture_default_str()
      ->check(CLI::Range(1, 4096));
  // One subcommand object runs whichever was chosen.
  return {cli,
          [options, calibration, check, calibrate] {
            (void)check;
            if (calibrate->parsed()) return run_model_calibrate(*calibration);
            return run_model_check(*options);
          },
          /*stops_on_signals=*/false};
}

}  // namespace rtmot::app
