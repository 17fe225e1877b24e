#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "platform/board.hpp"

namespace rtmot::platform {
namespace {

namespace fs = std::filesystem;

// Text as it appears on a Jetson Xavier NX with JetPack 5.1.2.
constexpr char xavier_model[] = "NVIDIA Jetson Xavier NX Developer Kit";
constexpr char l4t_35_4_1[] =
    "# R35 (release), REVISION: 4.1, GCID: 33958178, BOARD: t186ref, EABI: aarch64, DATE: Tue Aug  "
    "1 19:57:35 UTC 2023\n# KERNEL_VARIANT: oot\nTARGET_USERSPACE_LIB_DIR=nvidia\n";
constexpr char xavier_nvpmodel_conf[] =
    "< PARAM TYPE=FILE NAME=CPU_ONLINE >\nCORE_0 /sys/devices/system/cpu/cpu0/online\n"
    "< POWER_MODEL ID=0 NAME=MODE_15W_2CORE >\nCPU_ONLINE CORE_0 1\n"
    "< POWER_MODEL ID=1 NAME=MODE_15W_4CORE >\nCPU_ONLINE CORE_0 1\n"
    "< POWER_MODEL ID=2 NAME=MODE_15W_6CORE >\nCPU_ONLINE CORE_0 1\n"
    "< POWER_MODEL ID=8 NAME=MODE_20W_6CORE >\nCPU_ONLINE CORE_0 1\n"
    "< PM_CONFIG DEFAULT=2 >\n";

/// A directory tree standing in for "/", removed afterwards.
class FakeRoot : public testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("rtmot-board-" +
             std::string(testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  void write(const std::string& relative, const std::string& text) const {
    const fs::path path = root_ / relative;
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
  }

  fs::path root_;
};

TEST_F(FakeRoot, XavierNxWithPowerModeFromNvpmodelFiles) {
  write("proc/device-tree/model",
        std::string(xavier_model) + '\0');  // device-tree strings end in NUL
  write("etc/nv_tegra_release", l4t_35_4_1);
  write("etc/nvpmodel.conf", xavier_nvpmodel_conf);
  write("var/lib/nvpmodel/status", "pmode:0008 fmode:quiet\n");
  write("sys/devices/system/cpu/online", "0-5\n");

  const BoardInfo board = detect_board(root_);
  EXPECT_TRUE(board.is_jetson);
  EXPECT_EQ(board.model, xavier_model);
  EXPECT_EQ(board.l4t_release, "R35.4.1");
  EXPECT_EQ(board.power_mode, "MODE_20W_6CORE");
  EXPECT_EQ(board.cpu_count, 6);
  EXPECT_EQ(describe(board), "Jetson Xavier NX (L4T R35.4.1), power mode MODE_20W_6CORE");
}

TEST_F(FakeRoot, PowerModeFallsBackToTheConfDefault) {
  write("proc/device-tree/model", std::string(xavier_model) + '\0');
  write("etc/nv_tegra_release", l4t_35_4_1);
  write("etc/nvpmodel.conf", xavier_nvpmodel_conf);
  EXPECT_EQ(detect_board(root_).power_mode, "MODE_15W_6CORE");
}

TEST_F(FakeRoot, JetsonWithoutReleaseOrPowerModeSaysUnknown) {
  write("proc/device-tree/model", "NVIDIA Jetson Nano Developer Kit");
  const BoardInfo board = detect_board(root_);
  EXPECT_TRUE(board.is_jetson);
  EXPECT_EQ(board.l4t_release, "");
  EXPECT_EQ(describe(board), "Jetson Nano (L4T unknown), power mode unknown");
}

TEST_F(FakeRoot, OtherArmBoardIsNotAJetson) {
  write("proc/device-tree/model", std::string("Raspberry Pi 4 Model B Rev 1.4") + '\0');
  write("sys/devices/system/cpu/online", "0-3\n");
  const BoardInfo board = detect_board(root_);
  EXPECT_FALSE(board.is_jetson);
  EXPECT_EQ(board.cpu_count, 4);
  EXPECT_EQ(describe(board),
            "not a Jetson: Raspberry Pi 4 Model B Rev 1.4, " + board.machine + ", 4 CPUs");
}

TEST_F(FakeRoot, EmptyTreeIsAPc) {
  write("sys/devices/system/cpu/online", "0-1\n");
  const BoardInfo board = detect_board(root_);
  EXPECT_FALSE(board.is_jetson);
  EXPECT_EQ(board.model, "");
  EXPECT_EQ(board.power_mode, "");
  EXPECT_FALSE(board.machine.empty());
  EXPECT_EQ(describe(board), "not a Jetson: " + board.machine + ", 2 CPUs");
}

TEST(BoardParsers, L4tRelease) {
  EXPECT_EQ(parse_l4t_release(l4t_35_4_1), "R35.4.1");
  EXPECT_EQ(parse_l4t_release("# R32 (release), REVISION: 7.4, GCID: 33514132, BOARD: t210ref"),
            "R32.7.4");
  EXPECT_EQ(parse_l4t_release("garbage"), "");
}

TEST(BoardParsers, NvpmodelQuery) {
  EXPECT_EQ(parse_nvpmodel_query("NV Fan Mode:quiet\nNV Power Mode: MODE_15W_6CORE\n2\n"),
            "MODE_15W_6CORE");
  EXPECT_EQ(parse_nvpmodel_query("NV Power Mode: MAXN\n0\n"), "MAXN");
  EXPECT_EQ(parse_nvpmodel_query("nvpmodel: permission denied\n"), "");
}

TEST(BoardParsers, NvpmodelFilesIgnoreUnknownIds) {
  EXPECT_EQ(power_mode_from_nvpmodel_files(xavier_nvpmodel_conf, "pmode:0001"), "MODE_15W_4CORE");
  EXPECT_EQ(power_mode_from_nvpmodel_files(xavier_nvpmodel_conf, "pmode:0005"), "");
  EXPECT_EQ(power_mode_from_nvpmodel_files("", "pmode:0001"), "");
}

TEST(BoardParsers, CpuLists) {
  EXPECT_EQ(count_cpu_list("0"), 1);
  EXPECT_EQ(count_cpu_list("0-5"), 6);
  EXPECT_EQ(count_cpu_list("0-3,6,8-9"), 7);
  EXPECT_EQ(count_cpu_list(""), 0);
}

TEST(Board, ThisMachineIsDescribed) {
  const BoardInfo board = detect_board();
  EXPECT_GT(board.cpu_count, 0);
  EXPECT_FALSE(describe(board).empty());
}

}  // namespace
}  // namespace rtmot::platform
