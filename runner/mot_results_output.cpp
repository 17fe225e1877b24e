#include "runner/mot_results_output.hpp"

#include <algorithm>
#include <exception>
#include <system_error>
#include <utility>

#include "common/input_error.hpp"
#include "motio/mot_files.hpp"
#include "motio/processed_frames.hpp"
#include "motio/sequence_folders.hpp"
#include "platform/video_uri.hpp"
#include "runner/sequence_clock_source.hpp"

namespace rtmot::runner {
namespace {

namespace fs = std::filesystem;

constexpr const char* kField = "output.mot_results";

// A name not read from a seqinfo.ini, made plain; never empty.
std::string plain_name(const std::string& text, std::uint32_t stream_id) {
  std::string name = motio::plain_sequence_name(text);
  return name.empty() ? "stream-" + std::to_string(stream_id) : name;
}

// SEQ/seqinfo.ini for an image folder that is SEQ or SEQ/img1 (the MOTChallenge layout).
std::string sequence_name_of_folder(const fs::path& folder) {
  std::error_code error;
  for (const fs::path& dir : {folder, folder.parent_path()}) {
    if (dir.empty()) continue;
    const fs::path ini = dir / "seqinfo.ini";
    if (fs::is_regular_file(ini, error)) return motio::read_seqinfo(ini).name;
  }
  return {};
}

}  // namespace

std::string mot_results_name(const SourceConfig& source, std::uint32_t stream_id) {
  if (is_sequence_uri(source.uri)) {
    const fs::path dir = source.uri.substr(std::string(sequence_uri_scheme).size());
    return motio::read_seqinfo(dir / "seqinfo.ini").name;
  }
  platform::VideoUri uri;
  try {
    uri = platform::parse_video_uri(source.uri);
  } catch (const InputError&) {  // reported when the source opens
    return "stream-" + std::to_string(stream_id);
  }
  if (uri.kind == platform::SourceKind::images) {
    fs::path folder = fs::path(uri.location).lexically_normal();
    if (!folder.has_filename()) folder = folder.parent_path();  // "img1/" names img1
    const std::string sequence = sequence_name_of_folder(folder);
    if (!sequence.empty()) return sequence;
    return plain_name(folder.filename().string(), stream_id);
  }
  if (uri.kind == platform::SourceKind::file) {
    return plain_name(fs::path(uri.location).stem().string(), stream_id);
  }
  return "stream-" + std::to_string(stream_id);
}

std::vector<MotResultsTarget> mot_results_targets(const RunConfig& config) {
  const std::vector<SourceConfig> sources = source_list(config);
  std::vector<MotResultsTarget> targets;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const std::uint32_t stream_id = stream_id_of(config, i);
    std::string name = mot_results_name(sources[i], stream_id);
    for (std::size_t j = 0; j < targets.size(); ++j) {
      if (targets[j].name != name) continue;
      throw InputError(config.file, 0, kField,
                       "sources " + std::to_string(j) + " (" + sources[j].uri + ") and " +
                           std::to_string(i) + " (" + sources[i].uri +
                           ") would both write their results as '" + name +
                           "': run them into separate folders");
    }
    targets.push_back({stream_id, std::move(name)});
  }
  return targets;
}

fs::path mot_results_file(const fs::path& dir, const std::string& name) {
  return motio::sequence_file(dir, name, ".txt");
}

fs::path mot_frames_file(const fs::path& dir, const std::string& name) {
  return motio::processed_frames_file(dir, name);
}

fs::path mot_detections_file(const fs::path& dir, const std::string& name) {
  return motio::sequence_file(dir, name, ".det.txt");
}

MotResultsOutput::MotResultsOutput(const fs::path& dir,
                                   const std::vector<MotResultsTarget>& targets,
                                   bool with_detections) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error || !fs::is_directory(dir, error)) {
    throw InputError(dir.string(), 0, kField,
                     "cannot create the results folder" +
                         (error ? ": " + error.message() : std::string(": not a folder")));
  }
  streams_.reserve(targets.size());
  for (const MotResultsTarget& target : targets) {
    streams_.push_back(Stream{target.stream_id,
                              mot_frames_file(dir, target.name),
                              motio::ResultsWriter(mot_results_file(dir, target.name)),
                              std::nullopt,
                              {},
                              0});
    if (with_detections) streams_.back().detections.emplace(mot_detections_file(dir, target.name));
  }
}

void MotResultsOutput::consume(const pipeline::SinkFrame& frame) {
  const messages::FrameResult& result = frame.result;
  // An outage tick carries no picture, the end of a stream no tracks: nothing was processed.
  if (result.source_outage || result.end_of_stream || result.frame_number < 1 ||
      result.frame_number > motio::kMaxFrame) {
    return;
  }
  const auto stream = std::find_if(streams_.begin(), streams_.end(), [&](const Stream& s) {
    return s.stream_id == result.stream_id;
  });
  if (stream == streams_.end()) return;
  const int frame_number = static_cast<int>(result.frame_number);
  // A source's frame numbers ascend (platform/video_source.hpp): one that does not (a looped image
  // folder starting over) would make the results ambiguous, so it is left out.
  if (frame_number <= stream->last_written) return;
  stream->results.write(frame_number, result.tracks);
  stream->last_written = frame_number;
  if (result.predicted) return;
  stream->frames.push_back(frame_number);
  if (stream->detections) stream->detections->write(frame_number, frame.detections);
}

void MotResultsOutput::finish() {
  if (finished_) return;
  finished_ = true;
  // Every source's files, even if one fails; the first failure is reported.
  std::exception_ptr first;
  for (Stream& stream : streams_) {
    try {
      motio::publish_results_and_frames(stream.results, stream.frames_file, stream.frames);
    } catch (...) {
      if (!first) first = std::current_exception();
    }
    try {
      if (stream.detections) stream.detections->close();
    } catch (...) {
      if (!first) first = std::current_exception();
    }
  }
  if (first) std::rethrow_exception(first);
}

}  // namespace rtmot::runner
