#pragma once
// MOTChallenge files: seqinfo.ini, det/det.txt, gt/gt.txt and tracker results. Strict: a bad line
// throws rtmot::InputError naming file, line and field.
#include <filesystem>
#include <string>
#include <vector>

#include "tracker/box.hpp"

namespace rtmot::motio {

struct SequenceInfo {
  std::string name;
  double frame_rate{0.0};
  int length{0};  // frames
  int width{0};
  int height{0};
};

/// One row of a det.txt, gt.txt or results file: frame,id,x,y,w,h,conf[,class,visibility | ,x,y,z].
struct MotRow {
  int frame{0};  // 1-based
  int id{-1};
  tracker::Box box;
  float conf{1.F};
  int class_id{-1};  // gt of MOT16/17: class; -1 when absent
  float visibility{-1.F};
};

enum class MotFileKind { detections, ground_truth, results };

SequenceInfo read_seqinfo(const std::filesystem::path& ini_path);
std::vector<MotRow> read_mot_file(const std::filesystem::path& path, MotFileKind kind);
/// As above, and a row whose frame is beyond `max_frame` (the sequence's length) is an error too.
std::vector<MotRow> read_mot_file(const std::filesystem::path& path, MotFileKind kind,
                                  int max_frame);

/// Detections grouped by frame: result[f - 1] holds frame f's, for f in 1..length.
std::vector<std::vector<tracker::Detection>> detections_by_frame(const std::vector<MotRow>& rows,
                                                                 int length);

}  // namespace rtmot::motio
