// Records written whole (issue 11, class 7): `rtmot run` streaming messages to a JSON-lines file
// and a binary message file is stopped the hard ways, by SIGKILL and by a second SIGTERM (which
// ends it at once). A reader must find only whole records: every JSON line complete, the binary
// file's framing intact to its end. Before, stdio flushed its buffer wherever it filled, so the
// last record was cut. One cut remains possible and is allowed, only at the very end and only at
// a 4096-byte boundary of the file: common/output_file.hpp hands a buffer of whole records to one
// write(), and a process killed during it stops the kernel's copy between two pages (seen under
// qemu in the aarch64 stage: a 340-byte record cut at byte 294912 = 72 x 4096).
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <sstream>

#include "messages/message_file_reader.hpp"
#include "run_process.hpp"
#include "shared_data.hpp"
#include "workspace.hpp"

namespace rtmot::test {
namespace {

using std::chrono::milliseconds;

// 20,000 frames of eight boxes: the run is still writing when it is stopped.
std::string busy_det_file() {
  std::ostringstream det;
  for (int frame = 1; frame <= 20'000; ++frame) {
    for (int box = 0; box < 8; ++box) {
      det << frame << ",-1," << 10 + 70 * box << "," << 20 + frame % 50 << ",40,90,0.9,-1,-1,-1\n";
    }
  }
  return det.str();
}

constexpr std::uint64_t kPage = 4096;

// Returns the number of JSON lines.
int check_records_whole(const Workspace& ws) {
  std::string jsonl = read_text(ws.path("out.jsonl"));
  EXPECT_FALSE(jsonl.empty()) << "nothing was written before the stop";
  if (jsonl.empty()) return 0;
  if (jsonl.back() != '\n') {
    EXPECT_EQ(jsonl.size() % kPage, 0U)
        << "the last JSON line is cut at byte " << jsonl.size() << ", not at a page boundary";
    jsonl.erase(jsonl.rfind('\n') + 1);  // the torn tail a kill between two pages leaves
  }
  std::istringstream lines(jsonl);
  int count = 0;
  for (std::string line; std::getline(lines, line); ++count) {
    const bool whole = !line.empty() && line.front() == '{' && line.back() == '}';
    EXPECT_TRUE(whole) << "line " << count + 1 << " is not a whole record";
    if (!whole) break;
  }
  messages::MessageFileReader reader(ws.path("out.bin"));
  std::vector<std::uint8_t> record;
  messages::FileReadStatus status = messages::FileReadStatus::message;
  while ((status = reader.next(record)) == messages::FileReadStatus::message) {
  }
  if (status == messages::FileReadStatus::broken_framing) {
    const auto size = std::filesystem::file_size(ws.path("out.bin"));
    EXPECT_EQ(size % kPage, 0U) << reader.problem() << ", in a file of " << size << " bytes";
    EXPECT_NE(reader.problem().find("cut after"), std::string::npos) << reader.problem();
  } else {
    EXPECT_EQ(status, messages::FileReadStatus::end_of_file) << reader.problem();
  }
  EXPECT_GT(reader.records_read(), 0U);
  return count;
}

// The first signal goes 300 ms after the first whole records reached out.jsonl, so that there is
// something to check however slowly a loaded machine starts the run.
void run_and_stop(const std::string& name, std::vector<TimedSignal> signals) {
  Workspace ws(name);
  signals.front().after_file = ws.path("out.jsonl");
  ws.write("det.txt", busy_det_file());
  ws.write("run.yaml",
           "source:\n  uri: test://ball?width=64&height=48&num-buffers=20000\n"
           "playback:\n  mode: every-frame\ndetector:\n  kind: replay\n  det_file: " +
               ws.path("det.txt").string() + "\nstats_interval_s: 0\n");
  ProcessConditions conditions;
  conditions.signals = std::move(signals);
  const auto run =
      run_process({rtmot_binary(), "run", "--config", ws.path("run.yaml").string(), "--jsonl",
                   ws.path("out.jsonl").string(), "--binary", ws.path("out.bin").string()},
                  ws.dir(), conditions);
  ASSERT_FALSE(run.timed_out);
  // Stopped part-way (a second SIGTERM may find the clean stop already done: exit 0 or 143).
  EXPECT_LT(check_records_whole(ws), 20'000) << "the run ended before it was stopped";
}

TEST(RecordsWhole, AfterSigkill) {
  run_and_stop("records_sigkill", {{SIGKILL, milliseconds(300), "detector:"}});
}

TEST(RecordsWhole, AfterASecondStopSignal) {
  // The first asks for a clean stop; the second (SIGINT: two SIGTERMs sent together would merge
  // into one) ends the process at once, without one.
  run_and_stop("records_sigterm_twice",
               {{SIGTERM, milliseconds(300), "detector:"}, {SIGINT, milliseconds(0), ""}});
}

}  // namespace
}  // namespace rtmot::test
