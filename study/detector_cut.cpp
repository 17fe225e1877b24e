#include "study/detector_cut.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "mot/sequence_counts.hpp"
#include "study/synthetic_detector.hpp"
#include "tracker/presets.hpp"

namespace rtmot::study {
namespace {

int synthetic_index(const std::string& name) {
  const auto& specs = synthetic_detectors();
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (specs[i].name == name) {
      if (specs[i].held_back) throw std::invalid_argument(name + " is held back from every choice");
      return static_cast<int>(i);
    }
  }
  throw std::invalid_argument("no synthetic detector " + name);
}

// The sequence with the synthetic detector's detections scoring at least `cut` as its
// detections (StudyInput::detections): the rest is not copied.
LoadedSequence cut_sequence(const LoadedSequence& sequence, int synthetic, float cut,
                            long long& all, long long& kept) {
  LoadedSequence out;
  out.info = sequence.info;
  out.gt_rows = sequence.gt_rows;
  const motio::FrameDetections& source = sequence.synthetic.at(static_cast<std::size_t>(synthetic));
  std::vector<std::vector<tracker::Detection>> frames(
      static_cast<std::size_t>(sequence.info.length));
  for (int f = 1; f <= sequence.info.length; ++f) {
    for (const tracker::Detection& detection : source.at(f)) {
      ++all;
      if (detection.score < cut) continue;
      ++kept;
      frames[static_cast<std::size_t>(f - 1)].push_back(detection);
    }
  }
  out.detections = motio::FrameDetections::from_frames(std::move(frames));
  return out;
}

}  // namespace

std::vector<float> default_detector_cuts() {
  return {0.5F, 0.4F, 0.3F, 0.25F, 0.2F, 0.15F};
}

std::vector<DetectorCutTable> run_detector_cut_sweep(const std::vector<LoadedSequence>& dataset,
                                                     const std::vector<std::string>& presets,
                                                     const std::string& detector,
                                                     const std::vector<float>& cuts,
                                                     const std::vector<int>& intervals) {
  const int synthetic = synthetic_index(detector);
  std::vector<DetectorCutTable> tables;
  for (const std::string& preset : presets) tables.push_back({preset, detector, {}});
  for (const float cut : cuts) {
    long long all = 0;
    long long kept = 0;
    std::vector<LoadedSequence> sequences;
    for (const LoadedSequence& sequence : dataset)
      sequences.push_back(cut_sequence(sequence, synthetic, cut, all, kept));
    for (DetectorCutTable& table : tables) {
      const auto config = tracker::find_preset(table.preset);
      if (!config) throw std::invalid_argument("no preset " + table.preset);
      DetectorCutRow row;
      row.cut = cut;
      row.kept_share = all > 0 ? static_cast<double>(kept) / static_cast<double>(all) : 0.0;
      for (const int interval : intervals) {
        mot::SequenceCounts total;
        for (const LoadedSequence& sequence : sequences)
          total += track_and_count(sequence, StudyInput::detections, *config, interval, {});
        row.by_interval.push_back(mot::summarize(total));
      }
      table.rows.push_back(std::move(row));
    }
  }
  return tables;
}

std::string format_detector_cut_markdown(const std::vector<DetectorCutTable>& tables,
                                         const std::vector<int>& intervals) {
  std::string out = "| preset | detector | cut | detections kept |";
  std::string rule = "|---|---|---:|---:|";
  for (const int interval : intervals) {
    out += fmt::format(" N = {} MOTA / IDF1 |", interval);
    rule += "---:|";
  }
  out += "\n" + rule + "\n";
  for (const DetectorCutTable& table : tables) {
    for (const DetectorCutRow& row : table.rows) {
      out += fmt::format("| {} | {} | {:g} | {:.1f} % |", table.preset, table.detector, row.cut,
                         100.0 * row.kept_share);
      for (const mot::Metrics& m : row.by_interval)
        out += fmt::format(" {:.1f} / {:.1f} |", m.mota, m.idf1);
      out += "\n";
    }
  }
  return out;
}

}  // namespace rtmot::study
