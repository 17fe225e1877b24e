// The checked reader and the whole-record writer that every file input and output goes through:
// what used to be taken for empty or endless input, and what used to be left cut.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "common/output_file.hpp"

namespace rtmot {
namespace {

namespace fs = std::filesystem;

class Scratch {
 public:
  Scratch() : dir_(fs::temp_directory_path() / ("rtmot-common-" + std::to_string(::getpid()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~Scratch() { fs::remove_all(dir_); }
  fs::path path(const std::string& name) const { return dir_ / name; }

 private:
  fs::path dir_;
};

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

ExitCode code_of(const std::function<void()>& call, std::string* message = nullptr) {
  try {
    call();
  } catch (const InputError& error) {
    if (message != nullptr) *message = error.what();
    return error.exit_code();
  }
  ADD_FAILURE() << "no InputError thrown";
  return ExitCode::ok;
}

TEST(InputFile, ReadsARegularFileWhole) {
  Scratch scratch;
  std::ofstream(scratch.path("a.txt")) << "1,2,3\n4,5,6\n";
  EXPECT_EQ(read_text_file(scratch.path("a.txt")), "1,2,3\n4,5,6\n");
}

TEST(InputFile, AFolderIsNotTakenForAnEmptyFile) {
  Scratch scratch;
  fs::create_directories(scratch.path("det.txt"));
  std::string message;
  EXPECT_EQ(code_of([&] { read_text_file(scratch.path("det.txt")); }, &message),
            ExitCode::bad_input);
  EXPECT_NE(message.find("is a folder"), std::string::npos) << message;
}

TEST(InputFile, AFifoIsRefusedAtOnceNotWaitedOn) {
  Scratch scratch;
  ASSERT_EQ(::mkfifo(scratch.path("fifo").c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  std::string message;
  EXPECT_EQ(code_of([&] { read_text_file(scratch.path("fifo")); }, &message), ExitCode::bad_input);
  EXPECT_NE(message.find("FIFO"), std::string::npos) << message;
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

TEST(InputFile, AnEndlessDeviceIsRefused) {
  std::string message;
  EXPECT_EQ(code_of([&] { read_text_file("/dev/zero"); }, &message), ExitCode::bad_input);
  EXPECT_NE(message.find("device"), std::string::npos) << message;
}

TEST(InputFile, AFileAboveTheLimitIsRefusedBeforeItIsRead) {
  Scratch scratch;
  std::ofstream(scratch.path("big.txt")) << std::string(1000, 'x');
  std::string message;
  EXPECT_EQ(code_of([&] { read_text_file(scratch.path("big.txt"), 999); }, &message),
            ExitCode::bad_input);
  EXPECT_NE(message.find("1000 bytes"), std::string::npos) << message;
  EXPECT_EQ(read_text_file(scratch.path("big.txt"), 1000).size(), 1000U);
}

TEST(OutputFile, AFullDiskIsAnIoError) {
  if (!fs::is_character_file("/dev/full")) GTEST_SKIP() << "no /dev/full device";
  OutputFile file("/dev/full");
  std::string message;
  EXPECT_EQ(code_of(
                [&] {
                  file.write("0123456789\n");
                  file.flush();
                },
                &message),
            ExitCode::io_error);
  EXPECT_NE(message.find("/dev/full"), std::string::npos) << message;
}

TEST(OutputFile, PublishedOnCloseOnlyWhole) {
  Scratch scratch;
  const auto path = scratch.path("results.txt");
  std::ofstream(path) << "old\n";
  {
    OutputFile file(path, OutputFile::Publish::on_close);
    file.write("new\n");
    file.flush();
    EXPECT_EQ(slurp(path), "old\n") << "visible before close";
  }  // not closed: a stop or an error
  EXPECT_EQ(slurp(path), "old\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(scratch.path("")), fs::directory_iterator()), 1)
      << "the temporary is left behind";
  OutputFile file(path, OutputFile::Publish::on_close);
  file.write("new\n");
  file.close();
  EXPECT_EQ(slurp(path), "new\n");
}

// A file-size limit makes write() fail part-way as a full disk does (EFBIG instead of ENOSPC).
// What stays is whole records only, however the limit falls; the child reports the error's code.
TEST(OutputFile, AWriteThatFailsMidRecordLeavesWholeRecords) {
  Scratch scratch;
  const auto path = scratch.path("messages.jsonl");
  const std::string record = "{\"sequence\":12345,\"tracks\":[1,2,3]}\n";  // 36 bytes
  for (const rlim_t limit : {1000, 4097, 70000}) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      std::signal(SIGXFSZ, SIG_IGN);
      const rlimit fsize{limit, limit};
      ::setrlimit(RLIMIT_FSIZE, &fsize);
      try {
        OutputFile file(path);
        for (int i = 0; i < 100'000; ++i) file.write(record);
        file.close();
      } catch (const InputError& error) {
        ::_exit(static_cast<int>(error.exit_code()));
      }
      ::_exit(0);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), to_int(ExitCode::io_error)) << "limit " << limit;
    const std::string text = slurp(path);
    EXPECT_EQ(text.size() % record.size(), 0U) << "a record was cut at limit " << limit;
    EXPECT_GT(text.size(), limit - record.size() - 1) << "whole records were dropped";
  }
}

}  // namespace
}  // namespace rtmot

namespace rtmot {
namespace {

// A results file and its frames list are published both or neither: the list failing on a full
// disk leaves the results unpublished too (the old file kept, no temporary left).
TEST(OutputFile, FilesPublishedTogetherAppearBothOrNeither) {
  if (!fs::is_character_file("/dev/full")) GTEST_SKIP() << "no /dev/full device";
  Scratch scratch;
  const auto results = scratch.path("TUD-Campus.txt");
  std::ofstream(results) << "yesterday's\n";
  {
    OutputFile first(results, OutputFile::Publish::on_close);
    first.write("1,1,10,10,20,40,1,-1,-1,-1\n");
    OutputFile second("/dev/full", OutputFile::Publish::on_close);  // written in place: fails
    second.write("1\n");
    EXPECT_EQ(code_of([&] { publish_together(first, second); }), ExitCode::io_error);
  }
  EXPECT_EQ(slurp(results), "yesterday's\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(scratch.path("")), fs::directory_iterator()), 1);

  OutputFile first(results, OutputFile::Publish::on_close);
  first.write("new\n");
  OutputFile second(scratch.path("TUD-Campus.frames"), OutputFile::Publish::on_close);
  second.write("1\n");
  publish_together(first, second);
  EXPECT_EQ(slurp(results), "new\n");
  EXPECT_EQ(slurp(scratch.path("TUD-Campus.frames")), "1\n");
}

// A FIFO that no process reads is refused at once (open() used to wait for a reader for ever); a
// folder is refused with its kind.
TEST(OutputFile, AFifoWithoutReaderIsRefusedWithoutBlocking) {
  Scratch scratch;
  ASSERT_EQ(::mkfifo(scratch.path("fifo").c_str(), 0600), 0);
  for (const auto publish : {OutputFile::Publish::as_written, OutputFile::Publish::on_close,
                             OutputFile::Publish::appended}) {
    std::string message;
    EXPECT_EQ(code_of([&] { OutputFile file(scratch.path("fifo"), publish); }, &message),
              ExitCode::bad_input);
    EXPECT_NE(message.find("FIFO with no reader"), std::string::npos) << message;
  }
  std::string message;
  EXPECT_EQ(code_of([&] { OutputFile file(scratch.path(""), OutputFile::Publish::as_written); },
                    &message),
            ExitCode::bad_input);
  EXPECT_NE(message.find("folder"), std::string::npos) << message;
}

// A file emptied for writing is locked: a second writer is refused and empties nothing.
TEST(OutputFile, ASecondWriterOfOneFileIsRefused) {
  Scratch scratch;
  const auto path = scratch.path("tracks.jsonl");
  OutputFile first(path);
  first.write("{\"a\":1}\n");
  first.flush();
  std::string message;
  EXPECT_EQ(code_of([&] { OutputFile second(path); }, &message), ExitCode::bad_input);
  EXPECT_NE(message.find("another process"), std::string::npos) << message;
  EXPECT_EQ(slurp(path), "{\"a\":1}\n");
  OutputFile log(path, OutputFile::Publish::appended);  // appending takes no lock
  log.write("line\n");
  log.close();
  first.close();
  EXPECT_EQ(slurp(path), "{\"a\":1}\nline\n");
}

}  // namespace
}  // namespace rtmot
