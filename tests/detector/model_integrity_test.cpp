// The model's integrity at start-up: the checksums fetch_model.sh records, non-finite weights, and
// model paths that cannot be read. Each is an InputError with ExitCode::bad_model (exit 4) naming
// the file, never an internal error, and each is shown on a damaged copy of the real model.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "detector/model_checksum.hpp"
#include "detector/ssd_detector.hpp"
#include "shared_data.hpp"

namespace rtmot::detector {
namespace {

const std::string kName = "ssdlite_mobilenet_v2_coco";

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// Where each initializer's raw_data lies in a serialized ONNX model (ModelProto.graph = field 7,
// GraphProto.initializer = 5, TensorProto.name = 8, raw_data = 9): just enough protobuf to damage
// chosen weights of the real model without breaking its structure.
struct RawTensor {
  std::string name;
  std::size_t offset;
  std::size_t size;
};

std::uint64_t varint(const std::string& bytes, std::size_t& at) {
  std::uint64_t value = 0;
  for (int shift = 0; at < bytes.size(); shift += 7) {
    const auto byte = static_cast<unsigned char>(bytes[at++]);
    value |= std::uint64_t{byte & 0x7FU} << shift;
    if ((byte & 0x80U) == 0) break;
  }
  return value;
}

// Calls `field(number, offset, size)` for each length-delimited field of the message in
// [begin, end); skips the other wire types.
template <typename Field>
void for_each_field(const std::string& bytes, std::size_t begin, std::size_t end, Field field) {
  std::size_t at = begin;
  while (at < end) {
    const std::uint64_t key = varint(bytes, at);
    const auto number = static_cast<int>(key >> 3);
    switch (key & 7U) {
      case 0:
        varint(bytes, at);
        break;
      case 1:
        at += 8;
        break;
      case 5:
        at += 4;
        break;
      case 2: {
        const auto size = static_cast<std::size_t>(varint(bytes, at));
        field(number, at, size);
        at += size;
        break;
      }
      default:
        return;  // groups: not in ONNX
    }
  }
}

std::vector<RawTensor> raw_tensors(const std::string& model) {
  std::vector<RawTensor> tensors;
  for_each_field(model, 0, model.size(), [&](int number, std::size_t at, std::size_t size) {
    if (number != 7) return;  // graph
    for_each_field(model, at, at + size, [&](int n, std::size_t a, std::size_t s) {
      if (n != 5) return;  // initializer
      RawTensor tensor{"", 0, 0};
      for_each_field(model, a, a + s, [&](int f, std::size_t fa, std::size_t fs) {
        if (f == 8) tensor.name = model.substr(fa, fs);
        if (f == 9) tensor = {tensor.name, fa, fs};
      });
      if (tensor.size > 0) tensors.push_back(tensor);
    });
  });
  return tensors;
}

class ModelIntegrity : public ::testing::Test {
 protected:
  void SetUp() override {
    real_dir_ = test::source_path("models");
    if (!std::filesystem::exists(real_dir_ / (kName + ".onnx"))) {
      FAIL() << "missing model in " << real_dir_ << ": run scripts/fetch_model.sh";
    }
    dir_ = std::filesystem::temp_directory_path() /
           ("rtmot_integrity_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
    for (const char* extension : {".onnx", ".anchors.csv", ".sha256"}) {
      std::filesystem::copy_file(real_dir_ / (kName + extension), dir_ / (kName + extension));
    }
  }
  void TearDown() override {
    std::error_code ignored;
    std::filesystem::permissions(dir_, std::filesystem::perms::owner_all,
                                 std::filesystem::perm_options::add, ignored);
    std::filesystem::remove_all(dir_, ignored);
  }

  std::filesystem::path model() const { return dir_ / (kName + ".onnx"); }
  SsdConfig config() const {
    SsdConfig config;
    config.model_path = model();
    config.backend = BackendRequest::cpu;
    return config;
  }
  static InputError expect_model_error(const SsdConfig& config) {
    try {
      SsdDetector detector(config);
    } catch (const InputError& e) {
      EXPECT_EQ(e.exit_code(), ExitCode::bad_model) << e.what();
      return e;
    }
    ADD_FAILURE() << "no error for " << config.model_path;
    return InputError("", 0, "", "");
  }

  std::filesystem::path real_dir_;
  std::filesystem::path dir_;
};

TEST(Sha256, MatchesTheStandardTestVectors) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_F(ModelIntegrity, TheRealModelMatchesWhatSha256sumRecorded) {
  EXPECT_EQ(
      verify_model_checksums(dir_ / (kName + ".sha256"), model(), dir_ / (kName + ".anchors.csv")),
      2);
  SsdDetector detector(config());  // and loads
}

TEST_F(ModelIntegrity, OneChangedWeightIsNamedByTheChecksum) {
  std::string bytes = read_bytes(model());
  const auto tensors = raw_tensors(bytes);
  ASSERT_FALSE(tensors.empty());
  bytes[tensors.front().offset] ^= 0x01;  // the lowest mantissa bit of one weight: still loads
  write_bytes(model(), bytes);
  const InputError e = expect_model_error(config());
  EXPECT_EQ(e.file(), model().string());
  EXPECT_NE(std::string(e.what()).find("checksum mismatch"), std::string::npos) << e.what();
  // Without the checksum file the damage goes unnoticed: the network still runs.
  std::filesystem::remove(dir_ / (kName + ".sha256"));
  SsdDetector detector(config());
}

TEST_F(ModelIntegrity, ChangedAnchorsAreNamed) {
  std::string bytes = read_bytes(dir_ / (kName + ".anchors.csv"));
  bytes.back() = bytes.back() == '1' ? '2' : '1';
  write_bytes(dir_ / (kName + ".anchors.csv"), bytes);
  const InputError e = expect_model_error(config());
  EXPECT_EQ(e.file(), (dir_ / (kName + ".anchors.csv")).string());
}

TEST_F(ModelIntegrity, MalformedChecksumFileNamesItsLine) {
  write_bytes(dir_ / (kName + ".sha256"), "# rtmot\nnot a checksum line\n");
  const InputError e = expect_model_error(config());
  EXPECT_EQ(e.file(), (dir_ / (kName + ".sha256")).string());
  EXPECT_EQ(e.line(), 2);
}

TEST_F(ModelIntegrity, NonFiniteWeightsAreAClearError) {
  // NaN in every bias: the heads' outputs (no activation after them) become NaN, which would
  // otherwise silently compare false with every threshold and detect nothing.
  std::string bytes = read_bytes(model());
  int damaged = 0;
  for (const RawTensor& tensor : raw_tensors(bytes)) {
    if (tensor.name.rfind("B_", 0) != 0) continue;
    for (std::size_t i = 0; i < tensor.size; ++i) bytes[tensor.offset + i] = '\xff';  // NaN
    ++damaged;
  }
  ASSERT_GT(damaged, 10);
  write_bytes(model(), bytes);
  std::filesystem::remove(dir_ / (kName + ".sha256"));  // the check under test is the next one
  const InputError e = expect_model_error(config());
  EXPECT_EQ(e.file(), model().string());
  EXPECT_NE(std::string(e.what()).find("NaN"), std::string::npos) << e.what();
}

TEST_F(ModelIntegrity, ModelPathThatIsAFolder) {
  auto cfg = config();
  cfg.model_path = dir_;
  const InputError e = expect_model_error(cfg);
  EXPECT_NE(std::string(e.what()).find("folder"), std::string::npos) << e.what();
}

TEST_F(ModelIntegrity, ModelPathThatCannotBeLookedAt) {
  // A path component far longer than any file system allows (ENAMETOOLONG): the operating system
  // refuses to look, as it does for a folder without permission (which root, running CI, bypasses).
  auto cfg = config();
  cfg.model_path = dir_ / std::string(5000, 'x') / (kName + ".onnx");
  const InputError e = expect_model_error(cfg);
  EXPECT_EQ(e.file(), cfg.model_path.string());
  EXPECT_NE(std::string(e.what()).find("cannot access"), std::string::npos) << e.what();
}

TEST_F(ModelIntegrity, UnreadableModelFolder) {
  if (::geteuid() == 0) {
    // Root reads any folder; the folder case is ModelPathThatCannotBeLookedAt's error path.
    std::cout << "running as root: a folder without permission is readable; checked as non-root\n";
    return;
  }
  std::filesystem::permissions(dir_, std::filesystem::perms::none);
  const InputError e = expect_model_error(config());
  EXPECT_EQ(e.file(), model().string());
}

}  // namespace
}  // namespace rtmot::detector
