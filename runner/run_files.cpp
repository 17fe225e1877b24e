// run_setup.hpp's file checks: every file a run reads and writes, and the annotated video's target,
// before anything is opened for writing.
#include "runner/run_files.hpp"

#include <filesystem>

#include "common/input_error.hpp"
#include "detector/model_checksum.hpp"
#include "detector/ssd_detector.hpp"
#include "outputs/video_encoding.hpp"
#include "outputs/video_stream.hpp"
#include "outputs/video_target.hpp"
#include "platform/log_setup.hpp"
#include "platform/video_uri.hpp"
#include "runner/mot_results_output.hpp"
#include "runner/run_setup.hpp"
#include "runner/sequence_clock_source.hpp"

namespace rtmot::runner {

void check_run_files(const RunConfig& config) {
  std::vector<NamedFile> inputs{{config.file, "--config"}};
  const DetectorConfig& detector = config.detector;
  // A detections file named but not used (detector.kind ssd) is still the user's input file.
  inputs.push_back({detector.det_file, "detector.det_file"});
  if (detector.kind != DetectorKind::replay && !detector.model.empty()) {
    inputs.push_back({detector.model, "detector.model"});
    inputs.push_back({detector::checksum_path_of(detector.model), "the model's checksum file"});
    inputs.push_back({detector.anchors.empty() ? detector::default_anchors_path(detector.model)
                                               : std::filesystem::path(detector.anchors),
                      "detector.anchors"});
    if (detector.backend == detector::BackendRequest::xnnpack_int8) {
      inputs.push_back({detector.int8_ranges.empty()
                            ? detector::default_activation_ranges_path(detector.model)
                            : std::filesystem::path(detector.int8_ranges),
                        "detector.int8_ranges"});
    }
  }
  for (const SourceConfig& source : source_list(config)) {
    if (is_sequence_uri(source.uri)) {
      inputs.push_back(
          {std::filesystem::path(source.uri.substr(std::string(sequence_uri_scheme).size())) /
               "seqinfo.ini",
           "source.uri"});
      continue;
    }
    try {
      const platform::VideoUri uri = platform::parse_video_uri(source.uri);
      if (uri.kind == platform::SourceKind::file) inputs.push_back({uri.location, "source.uri"});
    } catch (const InputError&) {  // a malformed URI is reported when the source opens
    }
  }
  const OutputConfig& output = config.output;
  std::vector<NamedFile> outputs{{output.binary_file, "output.binary_file"},
                                 {output.jsonl_file, "output.jsonl_file"},
                                 {output.report_file, "output.report_file"},
                                 {output.web_save_to, "output.web_save_to"}};
  const auto& video = output.video;
  if (video && (video->kind == outputs::VideoTargetKind::mp4_file ||
                video->kind == outputs::VideoTargetKind::mkv_file)) {
    outputs.push_back({video->path, "output.video_file"});
  }
  if (!output.mot_results.empty()) {
    for (const auto& target : mot_results_targets(config)) {
      outputs.push_back({mot_results_file(output.mot_results, target.name), "output.mot_results"});
      outputs.push_back({mot_frames_file(output.mot_results, target.name), "output.mot_results"});
      if (output.mot_detections) {
        outputs.push_back(
            {mot_detections_file(output.mot_results, target.name), "output.mot_detections"});
      }
    }
  }
  platform::check_files_and_open_log(inputs, outputs);
}

void prepare_video_output(const RunConfig& config) {
  // First of all: no output may name an input or another output (nothing is opened for writing
  // before this).
  check_run_files(config);
  const auto& target = config.output.video;
  if (!target) return;
  const auto fail = [&](const std::string& why) {
    throw InputError(target->text, 0, "output.video_file", why);
  };
  if (target->kind != outputs::VideoTargetKind::display) {
    // The encoder's own field: a codec it does not encode, or one this GStreamer lacks.
    const auto choice =
        outputs::choose_encoder(config.output.video_encoding, outputs::gstreamer_has);
    if (choice.encoder == nullptr) {
      throw InputError(target->text, 0, "output.video_encoder", choice.problem);
    }
  }
  std::string problem = outputs::check_video_elements(*target, config.output.video_encoding);
  if (!problem.empty()) fail(problem);
  if (target->kind == outputs::VideoTargetKind::mp4_file ||
      target->kind == outputs::VideoTargetKind::mkv_file) {
    problem = outputs::prepare_video_file(*target);
    if (!problem.empty()) fail("cannot write the video: " + problem);
  }
}

}  // namespace rtmot::runner
