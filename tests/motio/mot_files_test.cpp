// The MOTChallenge readers: real files load; every kind of bad line names file, line and field.
#include "motio/mot_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.hpp"
#include "motio/frame_detections.hpp"
#include "motio/results_writer.hpp"
#include "scratch_folder.hpp"
#include "shared_data.hpp"

namespace rtmot::motio {
namespace {

namespace fs = std::filesystem;

class TempDir {
 public:
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path file = folder_.path() / name;
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }
  const fs::path& path() const { return folder_.path(); }

 private:
  test::ScratchFolder folder_{"mot-files"};
};

struct Failure {
  std::string file;
  int line{-1};
  std::string field;
  std::string message;
};

template <typename Call>
Failure failure_of(Call&& call) {
  try {
    call();
  } catch (const InputError& error) {
    return {error.file(), error.line(), error.field(), error.what()};
  }
  ADD_FAILURE() << "no InputError thrown";
  return {};
}

std::size_t count_lines(const fs::path& file) {
  std::ifstream in(file);
  std::size_t lines = 0;
  for (std::string line; std::getline(in, line);) lines += line.empty() ? 0 : 1;
  return lines;
}

TEST(MotFiles, LoadsEveryMot15TrainFile) {
  const auto dataset = test::shared_path("data/mot15-train");
  RTMOT_REQUIRE_FILE(dataset);
  for (const auto& entry : fs::directory_iterator(dataset)) {
    const SequenceInfo info = read_seqinfo(entry.path() / "seqinfo.ini");
    EXPECT_EQ(info.name, entry.path().filename().string());
    EXPECT_GT(info.frame_rate, 0.0);
    const auto gt =
        read_mot_file(entry.path() / "gt/gt.txt", MotFileKind::ground_truth, info.length);
    const auto det =
        read_mot_file(entry.path() / "det/det.txt", MotFileKind::detections, info.length);
    EXPECT_EQ(gt.size(), count_lines(entry.path() / "gt/gt.txt"));
    EXPECT_EQ(det.size(), count_lines(entry.path() / "det/det.txt"));
    const FrameDetections frames(det);
    EXPECT_LE(frames.last_frame(), info.length);
    std::size_t boxes = 0;
    for (int frame = 1; frame <= info.length; ++frame) boxes += frames.at(frame).size();
    EXPECT_EQ(boxes, det.size());
  }
}

TEST(MotFiles, ParsesTheFieldsOfAGroundTruthRow) {
  TempDir dir;
  const auto rows = read_mot_file(dir.write("gt.txt", "3,7,10.5,-2,40,80.25,0,2,0.75\r\n"),
                                  MotFileKind::ground_truth);
  ASSERT_EQ(rows.size(), 1U);
  EXPECT_EQ(rows[0].frame, 3);
  EXPECT_EQ(rows[0].id, 7);
  EXPECT_FLOAT_EQ(rows[0].box.x, 10.5F);
  EXPECT_FLOAT_EQ(rows[0].box.y, -2.F);
  EXPECT_FLOAT_EQ(rows[0].box.w, 40.F);
  EXPECT_FLOAT_EQ(rows[0].box.h, 80.25F);
  EXPECT_FLOAT_EQ(rows[0].conf, 0.F);
  EXPECT_EQ(rows[0].class_id, 2);
  EXPECT_FLOAT_EQ(rows[0].visibility, 0.75F);
}

struct BadLine {
  const char* name;
  MotFileKind kind;
  const char* text;  // the bad line is always line 2
  const char* field;
  const char* problem;  // part of the message
};

class BadLines : public ::testing::TestWithParam<BadLine> {};

TEST_P(BadLines, NameFileLineAndField) {
  const BadLine& bad = GetParam();
  TempDir dir;
  const auto file =
      dir.write("file.txt", std::string("1,1,10,10,20,40,1,-1,-1,-1\n") + bad.text + "\n");
  const Failure failure = failure_of([&] { read_mot_file(file, bad.kind, 100); });
  EXPECT_EQ(failure.file, file.string());
  EXPECT_EQ(failure.line, 2);
  EXPECT_EQ(failure.field, bad.field);
  EXPECT_NE(failure.message.find(bad.problem), std::string::npos) << failure.message;
}

const auto det = MotFileKind::detections;
const auto res = MotFileKind::results;
INSTANTIATE_TEST_SUITE_P(
    EachKind, BadLines,
    ::testing::Values(
        BadLine{"too_few_columns", det, "1,-1,10,10,20,40", "", "6 columns"},
        BadLine{"too_many_columns", res, "1,1,10,10,20,40,1,-1,-1,-1,5", "", "11 columns"},
        BadLine{"not_a_number", det, "1,-1,10,abc,20,40,0.9,-1,-1,-1", "y", "not a number"},
        BadLine{"empty_field", det, "1,-1,,10,20,40,0.9,-1,-1,-1", "x", "empty"},
        BadLine{"nan", res, "1,1,10,10,nan,40,1,-1,-1,-1", "w", "NaN or infinite"},
        BadLine{"inf", res, "1,1,10,10,20,-inf,1,-1,-1,-1", "h", "NaN or infinite"},
        BadLine{"zero_width", det, "1,-1,10,10,0,40,0.9,-1,-1,-1", "w", "not positive"},
        BadLine{"negative_height", det, "1,-1,10,10,20,-4,0.9,-1,-1,-1", "h", "not positive"},
        BadLine{"frame_zero", det, "0,-1,10,10,20,40,0.9,-1,-1,-1", "frame", "before the first"},
        BadLine{"frame_beyond", res, "101,1,10,10,20,40,1,-1,-1,-1", "frame", "beyond"},
        BadLine{"fractional_frame", res, "1.5,1,10,10,20,40,1,-1,-1,-1", "frame", "not an integer"},
        BadLine{"absurd_x", det, "1,-1,1e9,10,20,40,0.9,-1,-1,-1", "x", "outside"},
        BadLine{"absurd_width", det, "1,-1,10,10,5e7,40,0.9,-1,-1,-1", "w", "absurd"},
        BadLine{"negative_result_id", res, "1,-3,10,10,20,40,1,-1,-1,-1", "id", "negative"},
        BadLine{"huge_id", res, "1,99999999999,10,10,20,40,1,-1,-1,-1", "id", "out of range"},
        BadLine{"gt_conf_above_one", MotFileKind::ground_truth, "1,1,10,10,20,40,3,-1,-1,-1",
                "conf", "outside"},
        BadLine{"gt_bad_visibility", MotFileKind::ground_truth, "1,1,10,10,20,40,1,1,1.5",
                "visibility", "outside"},
        BadLine{"gt_bad_class", MotFileKind::ground_truth, "1,1,10,10,20,40,1,x,0.5", "class",
                "not a number"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(MotFiles, FrameBeyondTheLengthIsFineWhenTheLengthIsUnknown) {
  TempDir dir;
  const auto rows = read_mot_file(dir.write("r.txt", "500,1,1,1,2,2,1,-1,-1,-1\n"), res);
  EXPECT_EQ(rows.size(), 1U);
}

TEST(MotFiles, IntegralFloatsAreAcceptedForFramesAndIds) {
  TempDir dir;
  const auto rows = read_mot_file(dir.write("r.txt", "2.000,5.0,1,1,2,2,1,-1,-1,-1\n"), res);
  ASSERT_EQ(rows.size(), 1U);
  EXPECT_EQ(rows[0].frame, 2);
  EXPECT_EQ(rows[0].id, 5);
}

TEST(MotFiles, MissingFileNamesIt) {
  const Failure failure = failure_of([] { read_mot_file("/nonexistent/det.txt", det); });
  EXPECT_EQ(failure.file, "/nonexistent/det.txt");
  EXPECT_EQ(failure.line, 0);
}

TEST(Seqinfo, ReadsTheRequiredKeys) {
  TempDir dir;
  const auto info = read_seqinfo(dir.write("seqinfo.ini",
                                           "[Sequence]\nname=Walk\nimDir=img1\nframeRate="
                                           "14\nseqLength=795\nimWidth=768\nimHeight=576\n"));
  EXPECT_EQ(info.name, "Walk");
  EXPECT_DOUBLE_EQ(info.frame_rate, 14.0);
  EXPECT_EQ(info.length, 795);
  EXPECT_EQ(info.width, 768);
  EXPECT_EQ(info.height, 576);
}

TEST(Seqinfo, MissingKeyIsNamed) {
  TempDir dir;
  const auto file =
      dir.write("seqinfo.ini", "[Sequence]\nname=A\nframeRate=30\nimWidth=1\nimHeight=1\n");
  const Failure failure = failure_of([&] { read_seqinfo(file); });
  EXPECT_EQ(failure.field, "seqLength");
  EXPECT_EQ(failure.line, 0);
}

TEST(Seqinfo, BadValueNamesLineAndKey) {
  TempDir dir;
  const auto file = dir.write(
      "seqinfo.ini", "[Sequence]\nname=A\nframeRate=30\nseqLength=-5\nimWidth=1\nimHeight=1\n");
  const Failure failure = failure_of([&] { read_seqinfo(file); });
  EXPECT_EQ(failure.field, "seqLength");
  EXPECT_EQ(failure.line, 4);
}

TEST(Seqinfo, GarbageLineIsNamed) {
  TempDir dir;
  const auto file = dir.write("seqinfo.ini", "[Sequence]\nname=A\nthis is not ini\n");
  const Failure failure = failure_of([&] { read_seqinfo(file); });
  EXPECT_EQ(failure.line, 3);
}

TEST(ResultsWriter, WritesRowsThatReadBack) {
  TempDir dir;
  MotRow row;
  row.frame = 4;
  row.id = 9;
  row.box = {1.25F, 2.5F, 30.F, 60.75F};
  row.conf = 0.875F;
  const auto file = dir.path() / "out.txt";
  write_results(file, {row});
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "4,9,1.25,2.50,30.00,60.75,0.8750,-1,-1,-1");
  const auto back = read_mot_file(file, MotFileKind::results);
  ASSERT_EQ(back.size(), 1U);
  EXPECT_EQ(back[0].id, 9);
  EXPECT_FLOAT_EQ(back[0].box.h, 60.75F);
}

TEST(ResultsWriter, UnwritablePathIsAnInputError) {
  const Failure failure = failure_of([] { ResultsWriter("/nonexistent-dir/out.txt"); });
  EXPECT_EQ(failure.file, "/nonexistent-dir/out.txt");
}

TEST(ResultsWriter, ATinyBoxReadsBackAsABox) {
  TempDir dir;
  MotRow row;
  row.frame = 1;
  row.id = 1;
  row.box = {10.F, 20.F, 0.0001F, 0.004F};
  const auto file = dir.path() / "out.txt";
  write_results(file, {row});
  const auto back = read_mot_file(file, MotFileKind::results);
  ASSERT_EQ(back.size(), 1U);
  EXPECT_FLOAT_EQ(back[0].box.w, 0.0001F);
  EXPECT_FLOAT_EQ(back[0].box.h, 0.004F);
  EXPECT_EQ(results_size(12.345F), "12.35") << "ordinary sizes keep two decimals";
}

TEST(ResultsWriter, NothingAppearsWithoutClose) {
  TempDir dir;
  const auto file = dir.path() / "out.txt";
  {
    ResultsWriter writer(file);
    MotRow row;
    row.frame = 1;
    row.box = {0, 0, 1, 1};
    writer.write(row);
  }
  EXPECT_FALSE(fs::exists(file));
}

}  // namespace
}  // namespace rtmot::motio
