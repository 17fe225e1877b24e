// The ONNX metadata reader (detector/onnx_metadata.hpp) on files written byte by byte in
// protobuf's wire format, as the ONNX library writes a ModelProto: a description found among
// other fields and entries, one inside a damaged file not trusted, a value too long named. The
// fixture of model_layout_test.cpp checks it on a model the ONNX library itself wrote.
#include "detector/onnx_metadata.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "common/input_error.hpp"
#include "detector/model_contract.hpp"
#include "detector/model_description.hpp"

namespace rtmot::detector {
namespace {

namespace fs = std::filesystem;

std::string varint(std::uint64_t value) {
  std::string bytes;
  do {
    const auto low = static_cast<char>(value & 0x7f);
    value >>= 7;
    bytes += static_cast<char>(low | (value != 0 ? 0x80 : 0));
  } while (value != 0);
  return bytes;
}

std::string field(std::uint32_t number, const std::string& payload) {  // length-delimited
  return varint((number << 3) | 2) + varint(payload.size()) + payload;
}

std::string entry(const std::string& key, const std::string& value) {
  return field(14, field(1, key) + field(2, value));
}

// What precedes metadata in an ONNX file: ir_version (varint), producer_name, a graph of
// `graph_bytes` bytes, opset_import.
std::string model_head(std::size_t graph_bytes) {
  return varint(1 << 3) + varint(8) + field(2, "rtmot-test") +
         field(7, std::string(graph_bytes, '\x42')) +
         field(8, field(1, "") + varint(2 << 3) + varint(13));
}

class OnnxMetadata : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rtmot-onnx-metadata-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& bytes) const {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  fs::path dir_;
};

TEST_F(OnnxMetadata, FindsItsEntryAmongOtherFieldsAndEntries) {
  const fs::path model =
      write("m.onnx", model_head(100000) + entry("author", "someone") +
                          entry(kDescriptionMetadataKey, "layout: deltas\ninput:\n  size: 512\n") +
                          varint(5 << 3) + varint(3));  // model_version after the metadata
  EXPECT_EQ(onnx_metadata_value(model, kDescriptionMetadataKey, 1024),
            std::optional<std::string>("layout: deltas\ninput:\n  size: 512\n"));
  EXPECT_EQ(onnx_metadata_value(model, "author", 1024), std::optional<std::string>("someone"));
  EXPECT_EQ(onnx_metadata_value(model, "license", 1024), std::nullopt);
  const ModelDescription description = read_model_description(model);
  EXPECT_TRUE(description.inside_model);
  EXPECT_EQ(description.input_size, 512);
  EXPECT_EQ(described_by(description), model.string() + " (its metadata rtmot.model)");
}

TEST_F(OnnxMetadata, ADamagedFileYieldsNoDescription) {
  const std::string whole = model_head(5000) + entry(kDescriptionMetadataKey, "layout: deltas\n");
  // Cut inside the graph, inside the entry; a length past the end; a group (wire type 3).
  for (const std::size_t cut : {std::size_t{100}, whole.size() - 3}) {
    EXPECT_EQ(
        onnx_metadata_value(write("cut.onnx", whole.substr(0, cut)), kDescriptionMetadataKey, 1024),
        std::nullopt)
        << cut;
  }
  EXPECT_EQ(onnx_metadata_value(write("long.onnx", varint((7 << 3) | 2) + varint(1 << 30) + "x"),
                                kDescriptionMetadataKey, 1024),
            std::nullopt);
  EXPECT_EQ(onnx_metadata_value(write("group.onnx", varint((7 << 3) | 3) + whole),
                                kDescriptionMetadataKey, 1024),
            std::nullopt);
  EXPECT_EQ(onnx_metadata_value(dir_ / "absent.onnx", kDescriptionMetadataKey, 1024), std::nullopt);
  // Text is no ONNX model: no description, and the network's loader says what the file is.
  EXPECT_EQ(read_model_description(write("notes.onnx", "these are my notes\n")).file, fs::path());
}

TEST_F(OnnxMetadata, AValueTooLongIsNamedNotSkipped) {
  const fs::path model =
      write("big.onnx", model_head(10) + entry(kDescriptionMetadataKey, std::string(2000, '#')));
  try {
    onnx_metadata_value(model, kDescriptionMetadataKey, 1024);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.exit_code(), ExitCode::bad_model);
    EXPECT_EQ(e.file(), model.string());
    EXPECT_EQ(e.field(), "metadata rtmot.model");
    EXPECT_NE(std::string(e.what()).find("longer than 1024 bytes"), std::string::npos) << e.what();
  }
  // Another key's long value is none of this reader's business.
  EXPECT_EQ(onnx_metadata_value(model, "author", 1024), std::nullopt);
}

TEST_F(OnnxMetadata, ABrokenDescriptionInsideNamesTheModelLineAndField) {
  const fs::path model =
      write("broken.onnx",
            model_head(10) + entry(kDescriptionMetadataKey,
                                   "layout: deltas\ninput:\n  size: 300\n  colour: cmyk\n"));
  try {
    read_model_description(model);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.exit_code(), ExitCode::bad_model);
    EXPECT_EQ(e.file(), model.string() + " (metadata rtmot.model)");
    EXPECT_EQ(e.line(), 4);
    EXPECT_EQ(e.field(), "input.colour");
  }
}

}  // namespace
}  // namespace rtmot::detector
