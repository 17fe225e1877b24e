// Round three of the catalogue (issue 23, class 1): the detector's own files (the anchors CSV, the
// model's .sha256, the model) used to be opened with a plain ifstream: a FIFO there hung `run`
// forever, /dev/zero was read into memory, a failed read was taken for the end of the file. They
// now go through common/input_file (detector/model_files.hpp). Each case runs the real SSD's
// start-up on a model folder whose one file is replaced, and checks the exit code, the message and
// that no output was created.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>

#include "catalogue.hpp"
#include "shared_data.hpp"

namespace rtmot::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* kStem = "ssdlite_mobilenet_v2_coco";

// m/ holds the fetched model's three files (links to them, the checksum file copied), then `bad`
// (".anchors.csv", ".sha256" or ".onnx") is replaced by what `make` makes at its path.
std::function<void(Workspace&, Vars&)> model_folder_with(
    const std::string& bad, const std::function<void(const fs::path&)>& make) {
  return [=](Workspace& ws, Vars&) {
    fs::create_directories(ws.path("m"));
    for (const char* ext : {".onnx", ".anchors.csv", ".sha256"}) {
      const fs::path from = source_path(std::string("models/") + kStem + ext);
      const fs::path to = ws.path(std::string("m/") + kStem + ext);
      if (ext == bad) {
        make(to);
      } else if (std::string(ext) == ".sha256") {
        fs::copy_file(from, to);
      } else {
        fs::create_symlink(fs::canonical(from), to);
      }
    }
    ws.write("run.yaml",
             "source:\n  uri: test://ball?num-buffers=3\nplayback:\n  mode: every-frame\n"
             "detector:\n  kind: ssd\n  model: " +
                 ws.path(std::string("m/") + kStem + ".onnx").string() + "\n  backend: auto\n");
  };
}

void fifo(const fs::path& path) {
  ::mkfifo(path.c_str(), 0600);
}
void dev_zero(const fs::path& path) {
  fs::create_symlink("/dev/zero", path);
}

// The model folder as the setup left it: the checksum file (when not the bad one) unchanged, the
// bad file still what it was, nothing added.
std::function<void(const Workspace&)> model_folder_left_alone(const std::string& bad) {
  return [bad](const Workspace& ws) {
    const fs::path folder = ws.path("m");
    EXPECT_EQ(std::distance(fs::directory_iterator(folder), fs::directory_iterator()), 3);
    if (bad != ".sha256") {
      EXPECT_EQ(read_text(folder / (std::string(kStem) + ".sha256")),
                read_text(source_path(std::string("models/") + kStem + ".sha256")));
    }
    const fs::path replaced = folder / (std::string(kStem) + bad);
    EXPECT_TRUE(fs::is_fifo(fs::symlink_status(replaced)) ||
                fs::is_symlink(fs::symlink_status(replaced)))
        << replaced << " was replaced";
  };
}

CatalogueCase model_file_case(std::string name, std::string what, const std::string& ext,
                              void (*make)(const fs::path&), std::string mention) {
  return {std::move(name),
          std::move(what),
          model_folder_with(ext, make),
          {"run", "--config", "{dir}/run.yaml"},
          ExitCode::bad_model,
          {std::string(kStem) + ext, std::move(mention)},
          model_folder_left_alone(ext),
          ProcessConditions{},  // 60 s: the FIFO cases hung forever
          400};                 // MB: /dev/zero was read into memory
}

}  // namespace

std::vector<CatalogueCase> detector_file_cases() {
  return {
      model_file_case("run_anchors_is_a_fifo", "the anchors CSV is a FIFO (hung forever)",
                      ".anchors.csv", fifo, "FIFO"),
      model_file_case("run_anchors_is_dev_zero",
                      "the anchors CSV is /dev/zero (read into memory, 13.7 GB in 40 s)",
                      ".anchors.csv", dev_zero, "device"),
      model_file_case("run_checksum_is_a_fifo", "the model's .sha256 is a FIFO (hung forever)",
                      ".sha256", fifo, "FIFO"),
      model_file_case("run_checksum_is_dev_zero",
                      "the model's .sha256 is /dev/zero (read without end)", ".sha256", dev_zero,
                      "device"),
      model_file_case("run_model_is_a_fifo", "the model is a FIFO", ".onnx", fifo, "FIFO"),
      model_file_case("run_model_is_dev_zero", "the model is /dev/zero", ".onnx", dev_zero,
                      "device"),
  };
}

}  // namespace rtmot::test
