// Round three of the catalogue: the classes a hostile tester found in issue 23, each with cases of
// our own. Every case failed on the build before the fix (run the catalogue with
// RTMOT_CATALOGUE_BINARY=/path/to/old/rtmot to see it); docs/reliability.md lists them.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <string>

#include "catalogue.hpp"
#include "shared_data.hpp"

namespace rtmot::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* seq = "TUD-Campus";

std::string shared_det() {
  return read_text(shared_path(std::string("data/mot15-train/") + seq + "/det/det.txt"));
}
std::string shared_gt() {
  return read_text(shared_path(std::string("data/mot15-train/") + seq + "/gt/gt.txt"));
}

// A run on the replay detector over TUD-Campus's det.txt, timed by its seqinfo.ini (no images).
std::string replay_run(const Workspace& ws, const std::string& extra = "") {
  return "source:\n  uri: mot-seq://" + ws.path("data/TUD-Campus").string() +
         "\nplayback:\n  mode: every-frame\ndetector:\n  kind: replay\n  det_file: " +
         ws.path("data/TUD-Campus/det/det.txt").string() + "\n" + extra;
}

std::function<void(Workspace&, Vars&)> replay_config(const std::string& extra = "") {
  return [=](Workspace& ws, Vars&) {
    ws.copy_sequence(seq, "data/TUD-Campus");
    ws.write("run.yaml", replay_run(ws, extra));
  };
}

const std::vector<std::string> run_yaml = {"run", "--config", "{dir}/run.yaml"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// The file still holds exactly `text` (an input an output must not have touched).
std::function<void(const Workspace&)> unchanged(const std::string& relative,
                                                std::function<std::string()> text) {
  return [=](const Workspace& ws) {
    ASSERT_TRUE(fs::exists(ws.path(relative))) << relative << " was removed";
    EXPECT_EQ(read_text(ws.path(relative)), text()) << relative << " was changed";
  };
}

std::function<void(const Workspace&)> absent(const std::string& relative) {
  return [relative](const Workspace& ws) {
    EXPECT_FALSE(fs::exists(ws.path(relative))) << relative << " was created";
  };
}

std::function<void(const Workspace&)> all_of(
    std::vector<std::function<void(const Workspace&)>> checks) {
  return [checks](const Workspace& ws) {
    for (const auto& check : checks) check(ws);
  };
}

// Whole lines only (ends with a newline or is empty), at most `max_bytes`, no temporary beside it.
std::function<void(const Workspace&)> whole_text(const std::string& relative,
                                                 std::uintmax_t max_bytes) {
  return [=](const Workspace& ws) {
    ASSERT_TRUE(fs::exists(ws.path(relative))) << relative;
    const std::string text = read_text(ws.path(relative));
    EXPECT_TRUE(text.empty() || text.back() == '\n') << "last record cut: " << relative;
    EXPECT_LE(text.size(), max_bytes) << relative;
    for (const auto& entry : fs::directory_iterator(ws.path(relative).parent_path())) {
      EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos)
          << "temporary left behind: " << entry.path();
    }
  };
}

ProcessConditions with_disk_of(std::uint64_t bytes) {
  ProcessConditions conditions;
  conditions.file_size_limit = bytes;
  return conditions;
}

ProcessConditions with_stdout_on(const std::string& device) {
  ProcessConditions conditions;
  conditions.stdout_device = device;
  return conditions;
}

ProcessConditions with_time_limit(int seconds) {
  ProcessConditions conditions;
  conditions.time_limit = std::chrono::seconds(seconds);
  return conditions;
}

ProcessConditions with_memory_of(std::uint64_t bytes) {
  ProcessConditions conditions;
  conditions.time_limit = std::chrono::seconds(30);
  conditions.address_space_limit = bytes;
  return conditions;
}

std::string big_endian32(std::uint32_t value) {
  std::string bytes(4, '\0');
  for (int i = 0; i < 4; ++i) bytes[i] = static_cast<char>((value >> (24 - 8 * i)) & 0xFF);
  return bytes;
}

// The first bytes of a PNG declaring width x height (signature and IHDR; the rest is cut): what
// decides the memory a decoder would ask for.
std::string png_header(std::uint32_t width, std::uint32_t height) {
  return std::string("\x89PNG\r\n\x1a\n", 8) + big_endian32(13) + "IHDR" + big_endian32(width) +
         big_endian32(height) + std::string("\x08\x02\x00\x00\x00", 5) + big_endian32(0) +
         std::string(64, '\0');
}

// A JPEG's SOI, then a baseline start-of-frame declaring width x height.
std::string jpeg_header(std::uint16_t width, std::uint16_t height) {
  std::string bytes("\xFF\xD8\xFF\xC0\x00\x11\x08", 7);
  bytes += static_cast<char>(height >> 8);
  bytes += static_cast<char>(height & 0xFF);
  bytes += static_cast<char>(width >> 8);
  bytes += static_cast<char>(width & 0xFF);
  bytes += std::string("\x03\x01\x22\x00\x02\x11\x01\x03\x11\x01", 10);
  return bytes + std::string(64, '\0');
}

// An image folder holding one real frame (a 64x48 PNG written as PNM would need a codec: a BMP is
// plain bytes) and then `bad` under `name`.
std::function<void(Workspace&, Vars&)> image_folder_with(const std::string& name,
                                                         const std::string& bad) {
  return [=](Workspace& ws, Vars& vars) {
    if (!fs::exists(ws.path("run.yaml"))) replay_config()(ws, vars);
    // 8x8 24-bit BMP, bottom-up, grey.
    std::string bmp = "BM";
    const auto le32 = [](std::uint32_t v) {
      std::string b(4, '\0');
      for (int i = 0; i < 4; ++i) b[i] = static_cast<char>((v >> (8 * i)) & 0xFF);
      return b;
    };
    const std::uint32_t pixels = 8 * 8 * 3;
    bmp += le32(54 + pixels) + le32(0) + le32(54) + le32(40) + le32(8) + le32(8) +
           std::string("\x01\x00\x18\x00", 4) + le32(0) + le32(pixels) + le32(2835) + le32(2835) +
           le32(0) + le32(0) + std::string(pixels, '\x80');
    ws.write("frames/000001.bmp", bmp);
    ws.write("frames/" + name, bad);
  };
}

void make_fifo(const Workspace& ws, const std::string& relative) {
  fs::create_directories(ws.path(relative).parent_path());
  ASSERT_EQ(::mkfifo(ws.path(relative).c_str(), 0644), 0) << relative;
}

std::string seqinfo_with_rate(const std::string& rate) {
  return "[Sequence]\nname=TUD-Campus\nimDir=img1\nframeRate=" + rate +
         "\nseqLength=71\nimWidth=640\nimHeight=480\nimExt=.jpg\n";
}

}  // namespace

std::vector<CatalogueCase> round_three_cases() {
  std::vector<CatalogueCase> cases;

  // ---- 1. Files read outside the one input reader ------------------------------------------
  cases.push_back({"run_video_source_is_fifo",
                   "a video source path naming a FIFO (filesrc would block)",
                   [](Workspace& ws, Vars& vars) {
                     replay_config()(ws, vars);
                     make_fifo(ws, "video.mp4");
                   },
                   with(run_yaml, {"--source", "{dir}/video.mp4", "--jsonl", "{dir}/out.jsonl"}),
                   ExitCode::source_failed,
                   {"video.mp4", "FIFO"},
                   absent("out.jsonl"),
                   with_time_limit(30)});
  cases.push_back({"run_video_source_is_device",
                   "a video source path naming /dev/zero (never ends)",
                   [](Workspace& ws, Vars& vars) { replay_config()(ws, vars); },
                   with(run_yaml, {"--source", "/dev/zero", "--jsonl", "{dir}/out.jsonl"}),
                   ExitCode::source_failed,
                   {"/dev/zero", "device"},
                   absent("out.jsonl"),
                   with_time_limit(30)});
  cases.push_back({"run_image_folder_empty_image",
                   "an image folder whose first image is an empty file",
                   image_folder_with("000000.png", ""),
                   with(run_yaml, {"--source", "images://{dir}/frames"}),
                   ExitCode::source_failed,
                   {"000000.png", "not a PNG"}});

  cases.push_back({"count_lines_file_is_fifo",
                   "count --lines naming a FIFO (YAML::LoadFile blocked on it)",
                   [](Workspace& ws, Vars&) {
                     ws.copy_sequence(seq, "data/TUD-Campus");
                     make_fifo(ws, "lines.yaml");
                   },
                   {"count", "--dataset", "{dir}/data", "--lines", "{dir}/lines.yaml"},
                   ExitCode::bad_input,
                   {"lines.yaml", "FIFO"},
                   {},
                   with_time_limit(30)});
  cases.push_back({"count_lines_file_is_dev_zero",
                   "count --lines /dev/zero (read without end)",
                   [](Workspace& ws, Vars&) { ws.copy_sequence(seq, "data/TUD-Campus"); },
                   {"count", "--dataset", "{dir}/data", "--lines", "/dev/zero"},
                   ExitCode::bad_input,
                   {"/dev/zero", "device"},
                   {},
                   with_memory_of(1ULL << 30),
                   300});

  // ---- 3. An output that names an input or another output ----------------------------------
  cases.push_back({"run_jsonl_names_the_det_file",
                   "run --jsonl naming the replayed det.txt",
                   replay_config(),
                   with(run_yaml, {"--jsonl", "{dir}/data/TUD-Campus/det/det.txt"}),
                   ExitCode::bad_input,
                   {"det.txt", "same file", "detector.det_file"},
                   unchanged("data/TUD-Campus/det/det.txt", shared_det)});
  cases.push_back({"run_jsonl_hard_link_to_the_det_file",
                   "run --jsonl naming a hard link to the replayed det.txt",
                   [](Workspace& ws, Vars& vars) {
                     replay_config()(ws, vars);
                     fs::create_hard_link(ws.path("data/TUD-Campus/det/det.txt"),
                                          ws.path("tracks.jsonl"));
                   },
                   with(run_yaml, {"--jsonl", "{dir}/tracks.jsonl"}),
                   ExitCode::bad_input,
                   {"tracks.jsonl", "same file"},
                   unchanged("data/TUD-Campus/det/det.txt", shared_det)});
  cases.push_back({"run_report_through_a_link_to_the_config",
                   "run --report naming a symbolic link to the configuration",
                   [](Workspace& ws, Vars& vars) {
                     replay_config()(ws, vars);
                     fs::create_symlink(ws.path("run.yaml"), ws.path("report.json"));
                     vars["config_text"] = read_text(ws.path("run.yaml"));
                   },
                   with(run_yaml, {"--report", "{dir}/report.json"}),
                   ExitCode::bad_input,
                   {"report.json", "same file", "--config"},
                   [](const Workspace& ws) {
                     const std::string text = read_text(ws.path("run.yaml"));
                     EXPECT_NE(text.find("kind: replay"), std::string::npos)
                         << "the configuration was replaced";
                     EXPECT_TRUE(fs::is_symlink(ws.path("report.json")));
                   }});
  cases.push_back({"run_two_outputs_name_one_file",
                   "run --jsonl and --binary naming one new file (spelled two ways)",
                   replay_config(),
                   with(run_yaml, {"--jsonl", "{dir}/out/t", "--binary", "{dir}/out/../out/t"}),
                   ExitCode::bad_input,
                   {"same file", "output.binary_file", "output.jsonl_file"},
                   absent("out/t")});
  cases.push_back({"soak_jsonl_names_the_det_file",
                   "soak over a configuration whose output.jsonl_file is its det_file",
                   [](Workspace& ws, Vars&) {
                     ws.copy_sequence(seq, "data/TUD-Campus");
                     ws.write("run.yaml",
                              replay_run(ws, "output:\n  jsonl_file: " +
                                                 ws.path("data/TUD-Campus/det/det.txt").string() +
                                                 "\n"));
                   },
                   {"soak", "--config", "{dir}/run.yaml", "--duration", "1"},
                   ExitCode::bad_input,
                   {"det.txt", "same file", "output.jsonl_file"},
                   unchanged("data/TUD-Campus/det/det.txt", shared_det)});
  cases.push_back({"listen_jsonl_names_the_read_file",
                   "listen --read F --jsonl F",
                   [](Workspace& ws, Vars&) { ws.copy_sequence(seq, "data/TUD-Campus"); },
                   {"listen", "--read", "{dir}/data/TUD-Campus/det/det.txt", "--jsonl",
                    "{dir}/data/TUD-Campus/det/det.txt"},
                   ExitCode::bad_input,
                   {"det.txt", "same file", "--read"},
                   unchanged("data/TUD-Campus/det/det.txt", shared_det)});
  cases.push_back({"eval_csv_names_the_ground_truth",
                   "eval --csv naming the ground truth it scores against",
                   [](Workspace& ws, Vars&) {
                     ws.copy_sequence(seq, "data/TUD-Campus");
                     ws.write("res/TUD-Campus.txt", shared_gt());
                   },
                   {"eval", "--gt", "{dir}/data", "--results", "{dir}/res", "--csv",
                    "{dir}/data/TUD-Campus/gt/gt.txt"},
                   ExitCode::bad_input,
                   {"gt.txt", "same file", "--csv"},
                   unchanged("data/TUD-Campus/gt/gt.txt", shared_gt)});
  cases.push_back({"eval_json_names_a_results_file",
                   "eval --json naming one of the results files it scores",
                   [](Workspace& ws, Vars&) {
                     ws.copy_sequence(seq, "data/TUD-Campus");
                     ws.write("res/TUD-Campus.txt", shared_gt());
                   },
                   {"eval", "--gt", "{dir}/data", "--results", "{dir}/res", "--json",
                    "{dir}/res/TUD-Campus.txt"},
                   ExitCode::bad_input,
                   {"TUD-Campus.txt", "same file", "--json"},
                   unchanged("res/TUD-Campus.txt", shared_gt)});
  cases.push_back({"track_out_onto_the_detections",
                   "track --out onto the folder of the detections it reads",
                   [](Workspace& ws, Vars&) {
                     ws.copy_sequence(seq, "data/TUD-Campus");
                     ws.write("data/TUD-Campus/det/TUD-Campus.txt", shared_det());
                   },
                   {"track", "--dataset", "{dir}/data/TUD-Campus", "--out",
                    "{dir}/data/TUD-Campus/det", "--det", "det/TUD-Campus.txt"},
                   ExitCode::bad_input,
                   {"TUD-Campus.txt", "same file", "--out"},
                   unchanged("data/TUD-Campus/det/TUD-Campus.txt", shared_det)});

  // ---- 6. Memory out of proportion to the input --------------------------------------------
  cases.push_back({"run_image_folder_png_declares_20000_square",
                   "an image folder with a 100-byte PNG declaring 20000x20000 pixels",
                   image_folder_with("000000.png", png_header(20000, 20000)),
                   with(run_yaml, {"--source", "images://{dir}/frames"}),
                   ExitCode::source_failed,
                   {"000000.png", "20000x20000"},
                   {},
                   with_memory_of(1ULL << 30),
                   400});
  cases.push_back({"run_image_folder_jpeg_declares_60000_wide",
                   "an image folder whose first image is a JPEG header declaring 60000x9000",
                   image_folder_with("000000.jpg", jpeg_header(60000, 9000)),
                   with(run_yaml, {"--source", "images://{dir}/frames"}),
                   ExitCode::source_failed,
                   {"000000.jpg", "60000x9000"},
                   {},
                   with_memory_of(1ULL << 30),
                   400});
  cases.push_back({"track_det_file_of_blank_lines",
                   "det.txt: 96 MB of blank lines before the rows, under a 2 GB address limit",
                   [](Workspace& ws, Vars&) {
                     ws.copy_sequence(seq, "data/TUD-Campus");
                     ws.write("data/TUD-Campus/det/det.txt",
                              std::string(96U << 20, '\n') + shared_det());
                   },
                   {"track", "--dataset", "{dir}/data", "--out", "{dir}/out"},
                   ExitCode::ok,
                   {},
                   whole_text("out/TUD-Campus.txt", 1U << 20),
                   with_memory_of(2ULL << 30),
                   600});

  // ---- 7. SIGXFSZ: the harness no longer ignores it (run_process.cpp) -----------------------
  cases.push_back({"run_jsonl_under_a_file_size_limit",
                   "run --jsonl under ulimit -f (8 KB): SIGXFSZ left at its default",
                   replay_config(),
                   with(run_yaml, {"--jsonl", "{dir}/out/tracks.jsonl"}),
                   ExitCode::io_error,
                   {"tracks.jsonl", "File too large"},
                   whole_text("out/tracks.jsonl", 8192),
                   with_disk_of(8192)});
  cases.push_back(
      {"run_binary_under_a_file_size_limit",
       "run --binary under ulimit -f (8 KB)",
       replay_config(),
       with(run_yaml, {"--binary", "{dir}/out/tracks.bin"}),
       ExitCode::io_error,
       {"tracks.bin", "File too large"},
       [](const Workspace& ws) { EXPECT_LE(fs::file_size(ws.path("out/tracks.bin")), 8192U); },
       with_disk_of(8192)});
  cases.push_back({"track_results_under_a_file_size_limit",
                   "track under ulimit -f (4 KB): the results file cannot be whole",
                   [](Workspace& ws, Vars&) { ws.copy_sequence(seq, "data/TUD-Campus"); },
                   {"track", "--dataset", "{dir}/data", "--out", "{dir}/out"},
                   ExitCode::io_error,
                   {"TUD-Campus.txt", "File too large"},
                   all_of({absent("out/TUD-Campus.txt"), no_temporaries("out")}),
                   with_disk_of(4096)});

  // ---- 8. The video encoder's constraints ---------------------------------------------------
  cases.push_back({"run_video_of_odd_size",
                   "an annotated mp4 of a 33x17 source (x264 takes even sides of 16 or more)",
                   replay_config(),
                   with(run_yaml, {"--source", "test://ball?width=33&height=17&num-buffers=20",
                                   "--video-out", "{dir}/out/video.mp4"}),
                   ExitCode::ok,
                   {},
                   [](const Workspace& ws) {
                     ASSERT_TRUE(fs::exists(ws.path("out/video.mp4")));
                     EXPECT_GT(fs::file_size(ws.path("out/video.mp4")), 1000U);
                     EXPECT_NE(read_text(ws.path("out/video.mp4")).find("moov"), std::string::npos)
                         << "no index: not playable";
                     no_temporaries("out")(ws);
                   }});
  cases.push_back(
      {"run_video_of_8x8_images",
       "an annotated mp4 of a folder of 8x8 images",
       [](Workspace& ws, Vars& vars) {
         replay_config()(ws, vars);
         image_folder_with("000002.bmp.txt", "")(ws, vars);
         fs::copy_file(ws.path("frames/000001.bmp"), ws.path("frames/000002.bmp"));
       },
       with(run_yaml, {"--source", "images://{dir}/frames", "--video-out", "{dir}/out/video.mp4"}),
       ExitCode::ok,
       {},
       [](const Workspace& ws) {
         ASSERT_TRUE(fs::exists(ws.path("out/video.mp4")));
         EXPECT_NE(read_text(ws.path("out/video.mp4")).find("moov"), std::string::npos);
       }});
  cases.push_back({"run_video_kept_when_the_source_fails",
                   "an existing video named by --video-out, and a source that cannot open",
                   [](Workspace& ws, Vars& vars) {
                     replay_config()(ws, vars);
                     ws.write("out/video.mp4", "yesterday's video");
                   },
                   with(run_yaml, {"--source", "/dev/zero", "--video-out", "{dir}/out/video.mp4"}),
                   ExitCode::source_failed,
                   {"/dev/zero"},
                   [](const Workspace& ws) {
                     EXPECT_EQ(read_text(ws.path("out/video.mp4")), "yesterday's video");
                     no_temporaries("out")(ws);
                   }});

  // ---- 9. MQTT topics ----------------------------------------------------------------------
  cases.push_back(
      {"run_mqtt_topic_with_wildcard",
       "run --mqtt publishing to a topic with a + wildcard",
       replay_config(),
       with(run_yaml, {"--mqtt", "mqtt://127.0.0.1:1/site/+/tracks", "--jsonl", "{dir}/out.jsonl"}),
       ExitCode::usage,
       {"--mqtt", "wildcards"},
       absent("out.jsonl")});
  cases.push_back({"run_mqtt_topic_hash_in_the_middle",
                   "output.mqtt topic a/#/b in the configuration",
                   replay_config("output:\n  mqtt: mqtt://127.0.0.1:1/a/#/b\n"),
                   run_yaml,
                   ExitCode::bad_input,
                   {"output.mqtt", "run.yaml"}});
  cases.push_back({"run_mqtt_topic_malformed_utf8",
                   "run --mqtt topic holding a byte that is not UTF-8",
                   replay_config(),
                   with(run_yaml, {"--mqtt", "mqtt://127.0.0.1:1/caf\xE9"}),
                   ExitCode::usage,
                   {"--mqtt", "UTF-8"}});
  cases.push_back({"run_mqtt_topic_sys",
                   "run --mqtt publishing into the broker's $SYS tree",
                   replay_config(),
                   with(run_yaml, {"--mqtt", "mqtt://127.0.0.1:1/$SYS/tracks"}),
                   ExitCode::usage,
                   {"--mqtt", "$SYS"}});
  cases.push_back({"listen_mqtt_filter_hash_not_last",
                   "listen --mqtt with the filter a/b# (# not a whole level)",
                   [](Workspace&, Vars&) {},
                   {"listen", "--mqtt", "mqtt://127.0.0.1:1/a/b#", "--jsonl", "{dir}/out.jsonl"},
                   ExitCode::usage,
                   {"--mqtt", "topic filter"},
                   absent("out.jsonl")});
  cases.push_back({"listen_mqtt_filter_plus_inside_a_level",
                   "listen --mqtt with the filter a/b+/c",
                   [](Workspace&, Vars&) {},
                   {"listen", "--mqtt", "mqtt://127.0.0.1:1/a/b+/c"},
                   ExitCode::usage,
                   {"--mqtt", "topic filter"}});

  // ---- 10. Rates that are positive but absurd ------------------------------------------------
  cases.push_back(
      {"run_images_fps_1e_300",
       "images://DIR?fps=1e-300",
       image_folder_with("000002.bmp.txt", ""),
       with(run_yaml, {"--source", "images://{dir}/frames?fps=1e-300", "--playback", "realtime"}),
       ExitCode::source_failed,
       {"fps", "1e-300"},
       {},
       with_time_limit(30)});
  cases.push_back({"run_test_source_fps_1e_300",
                   "test://ball?fps=1e-300",
                   replay_config(),
                   with(run_yaml, {"--source", "test://ball?fps=1e-300&num-buffers=5"}),
                   ExitCode::source_failed,
                   {"fps", "1e-300"}});
  cases.push_back({"run_seqinfo_frame_rate_1e_300",
                   "mot-seq:// source whose seqinfo.ini says frameRate=1e-300, realtime",
                   [](Workspace& ws, Vars& vars) {
                     replay_config("")(ws, vars);
                     ws.write("data/TUD-Campus/seqinfo.ini", seqinfo_with_rate("1e-300"));
                   },
                   with(run_yaml, {"--playback", "realtime"}),
                   ExitCode::bad_input,
                   {"seqinfo.ini:4", "frameRate"},
                   {},
                   with_time_limit(30)});
  cases.push_back({"track_seqinfo_frame_rate_below_the_bound",
                   "seqinfo.ini frameRate=0.001 (one frame in 17 minutes)",
                   [](Workspace& ws, Vars&) {
                     ws.copy_sequence(seq, "data/TUD-Campus");
                     ws.write("data/TUD-Campus/seqinfo.ini", seqinfo_with_rate("0.001"));
                   },
                   {"track", "--dataset", "{dir}/data", "--out", "{dir}/out"},
                   ExitCode::bad_input,
                   {"seqinfo.ini:4", "frameRate", "0.01"},
                   absent("out/TUD-Campus.txt")});
  cases.push_back({"run_config_source_fps_1e_300",
                   "source.fps: 1e-300 in the configuration",
                   [](Workspace& ws, Vars& vars) {
                     replay_config("")(ws, vars);
                     std::string text = read_text(ws.path("run.yaml"));
                     text.insert(text.find("\nplayback:"), "\n  fps: 1e-300");
                     ws.write("run.yaml", text);
                   },
                   run_yaml,
                   ExitCode::bad_input,
                   {"run.yaml", "fps"}});

  // ---- 11. Smaller ones --------------------------------------------------------------------
  cases.push_back({"run_file_uri_with_percent_00",
                   "file:// URI holding %00 (decoded, it cut the path at the NUL)",
                   [](Workspace& ws, Vars& vars) {
                     replay_config()(ws, vars);
                     ws.write("video", "not a video");
                   },
                   with(run_yaml, {"--source", "file://{dir}/video%00.mp4"}),
                   ExitCode::source_failed,
                   {"%00", "NUL"}});
  cases.push_back({"run_images_uri_with_percent_00",
                   "images:// URI holding %00",
                   image_folder_with("000002.bmp.txt", ""),
                   with(run_yaml, {"--source", "images://{dir}/frames%00x"}),
                   ExitCode::source_failed,
                   {"%00"}});
  cases.push_back(
      {"run_v4l2_names_a_regular_file",
       "v4l2:// naming a regular file (was retried forever as a cold start)",
       [](Workspace& ws, Vars& vars) {
         replay_config()(ws, vars);
         ws.write("video0", "not a device");
       },
       with(run_yaml, {"--source", "v4l2://{dir}/video0", "--jsonl", "{dir}/out.jsonl"}),
       ExitCode::source_failed,
       {"video0", "not a device"},
       absent("out.jsonl"),
       with_time_limit(30)});
  cases.push_back({"run_v4l2_names_a_folder",
                   "v4l2:// naming a folder",
                   [](Workspace& ws, Vars& vars) { replay_config()(ws, vars); },
                   with(run_yaml, {"--source", "v4l2://{dir}/data"}),
                   ExitCode::source_failed,
                   {"a folder"},
                   {},
                   with_time_limit(30)});
  {
    CatalogueCase full{
        "eval_stdout_on_a_full_device",
        "eval with stdout on /dev/full: the table is lost",
        [](Workspace& ws, Vars&) {
          ws.copy_sequence(seq, "data/TUD-Campus");
          ws.write("res/TUD-Campus.txt", shared_gt());
        },
        {"eval", "--gt", "{dir}/data", "--results", "{dir}/res", "--csv", "{dir}/table.csv"},
        ExitCode::io_error,
        {"stdout"},
        whole_text("table.csv", 1U << 20),
        with_stdout_on("/dev/full")};
    cases.push_back(std::move(full));
  }
  cases.push_back({"track_stdout_on_a_full_device",
                   "track with stdout on /dev/full: its summary is lost, results stay whole",
                   [](Workspace& ws, Vars&) { ws.copy_sequence(seq, "data/TUD-Campus"); },
                   {"track", "--dataset", "{dir}/data", "--out", "{dir}/out"},
                   ExitCode::io_error,
                   {"stdout"},
                   whole_text("out/TUD-Campus.txt", 1U << 20),
                   with_stdout_on("/dev/full")});
  return cases;
}

}  // namespace rtmot::test
