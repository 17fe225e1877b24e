// Temporaries of writers that were killed (common/stale_temporaries.hpp): a results file's writer
// killed by SIGKILL mid-run leaves PATH.tmp-PID; the next writer of PATH removes it, and nothing
// of a writer that still runs, of another output or of a name that only looks alike.
#include "common/stale_temporaries.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "common/output_file.hpp"
#include "scratch_folder.hpp"

namespace rtmot {
namespace {

namespace fs = std::filesystem;

std::set<std::string> names_in(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.insert(entry.path().filename());
  return names;
}

// A child that writes PATH on close and is killed (SIGKILL) before it closes: its temporary stays.
pid_t killed_writer_of(const fs::path& path) {
  int ready[2];
  if (::pipe(ready) != 0) return -1;
  const pid_t child = ::fork();
  if (child == 0) {
    OutputFile file(path, OutputFile::Publish::on_close);
    file.write("1,1,10,20,30,40,0.9,-1,-1,-1\n");
    file.flush();
    const char byte = 'x';
    (void)!::write(ready[1], &byte, 1);
    ::pause();
    ::_exit(0);
  }
  char byte = 0;
  (void)!::read(ready[0], &byte, 1);
  ::close(ready[0]);
  ::close(ready[1]);
  ::kill(child, SIGKILL);
  ::waitpid(child, nullptr, 0);
  return child;
}

TEST(StaleTemporaries, TheNextWriterRemovesTheKilledWritersTemporaryOnly) {
  const test::ScratchFolder scratch("stale");
  const fs::path path = scratch.path() / "results.txt";
  const pid_t killed = killed_writer_of(path);
  ASSERT_GT(killed, 0);
  const std::string left = "results.txt.tmp-" + std::to_string(killed);
  ASSERT_EQ(names_in(scratch.path()), std::set<std::string>{left});

  // A writer that still runs (this test's parent, as good as any live process), look-alikes and
  // another output's temporary of the same dead process.
  const std::string live = "results.txt.tmp-" + std::to_string(::getppid());
  const std::string other = "other.txt.tmp-" + std::to_string(killed);
  for (const std::string& name :
       {live, other, std::string("results.txt.tmp-x1"), std::string("results.txt.tmp-"),
        std::string("results.txt.tmp-0")}) {
    std::ofstream(scratch.path() / name) << "x";
  }
  OutputFile file(path, OutputFile::Publish::on_close);
  file.write("2,1,10,20,30,40,0.9,-1,-1,-1\n");
  file.close();
  EXPECT_EQ(names_in(scratch.path()),
            (std::set<std::string>{"results.txt", live, other, "results.txt.tmp-x1",
                                   "results.txt.tmp-", "results.txt.tmp-0"}));
  EXPECT_EQ(remove_stale_temporaries(path), 0U);  // nothing left to remove
}

TEST(StaleTemporaries, ANameInTheCurrentFolderAndAMissingFolderAreFine) {
  EXPECT_EQ(remove_stale_temporaries("rtmot-no-such-output-here.txt"), 0U);
  EXPECT_EQ(remove_stale_temporaries("/nonexistent-rtmot/folder/out.txt"), 0U);
  EXPECT_EQ(temporary_path_for("a/b.txt"), fs::path("a/b.txt.tmp-" + std::to_string(::getpid())));
}

}  // namespace
}  // namespace rtmot
