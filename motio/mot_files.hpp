#pragma once
// MOTChallenge files: seqinfo.ini, det/det.txt, gt/gt.txt and tracker results. Strict: a bad line
// throws rtmot::InputError naming file, line and field.
#include <filesystem>
#include <string>
#include <vector>

#include "tracker/box.hpp"

namespace rtmot::motio {

/// The largest frame number (and sequence length, and frame interval) rtmot accepts: 10 million
/// frames are 46 days at 25 fps. Frame arithmetic stays far from int's limit.
constexpr int kMaxFrame = 10'000'000;

struct SequenceInfo {
  std::string name;  // a plain file name (outputs are named after it): see check_sequence_name
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
/// Throws InputError (file, line, field "name") unless `name` is a plain file name: letters,
/// digits and - _ . + (not first: . or -), at most 128 bytes. No folders, no "..", no "/abs".
void check_sequence_name(const std::string& name, const std::string& file, int line);
/// `text` made a name check_sequence_name() accepts: every other character replaced by '_', a
/// leading . or - too, cut to 128 bytes; empty stays empty.
std::string plain_sequence_name(const std::string& text);
std::vector<MotRow> read_mot_file(const std::filesystem::path& path, MotFileKind kind);
/// As above, and a row whose frame is beyond `max_frame` (the sequence's length) is an error too.
std::vector<MotRow> read_mot_file(const std::filesystem::path& path, MotFileKind kind,
                                  int max_frame);

}  // namespace rtmot::motio
