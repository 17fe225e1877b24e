#include "detector/model_checksum.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <sstream>
#include <system_error>
#include <vector>

#include "common/input_error.hpp"
#include "detector/model_files.hpp"

namespace rtmot::detector {
namespace {

// SHA-256 (FIPS 180-4). Written out here because neither OpenCV nor the C++ library has one and
// the product links no crypto library; it only has to match sha256sum, not resist anything.
class Sha256 {
 public:
  void update(const unsigned char* data, std::size_t size) {
    length_ += size;
    while (size > 0) {
      const std::size_t take = std::min(size, block_.size() - used_);
      std::memcpy(block_.data() + used_, data, take);
      used_ += take;
      data += take;
      size -= take;
      if (used_ == block_.size()) {
        compress(block_.data());
        used_ = 0;
      }
    }
  }

  std::string hex() {
    const std::uint64_t bits = length_ * 8;
    const unsigned char one = 0x80;
    const unsigned char zero = 0;
    update(&one, 1);
    while (used_ != 56) update(&zero, 1);
    unsigned char tail[8];
    for (int i = 0; i < 8; ++i) tail[i] = static_cast<unsigned char>(bits >> (56 - 8 * i));
    update(tail, 8);
    static const char digits[] = "0123456789abcdef";
    std::string text;
    for (const std::uint32_t word : state_) {
      for (int shift = 28; shift >= 0; shift -= 4) text += digits[(word >> shift) & 0xF];
    }
    return text;
  }

 private:
  static std::uint32_t rotr(std::uint32_t x, int n) { return (x >> n) | (x << (32 - n)); }

  void compress(const unsigned char* p) {
    static constexpr std::uint32_t k[64] = {
        0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4,
        0xab1c5ed5, 0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe,
        0x9bdc06a7, 0xc19bf174, 0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f,
        0x4a7484aa, 0x5cb0a9dc, 0x76f988da, 0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7,
        0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967, 0x27b70a85, 0x2e1b2138, 0x4d2c6dfc,
        0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85, 0xa2bfe8a1, 0xa81a664b,
        0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070, 0x19a4c116,
        0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
        0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7,
        0xc67178f2};
    std::uint32_t w[64];
    for (int i = 0; i < 16; ++i) {
      w[i] = (std::uint32_t{p[4 * i]} << 24) | (std::uint32_t{p[4 * i + 1]} << 16) |
             (std::uint32_t{p[4 * i + 2]} << 8) | std::uint32_t{p[4 * i + 3]};
    }
    for (int i = 16; i < 64; ++i) {
      const std::uint32_t s0 = rotr(w[i - 15], 7) ^ rotr(w[i - 15], 18) ^ (w[i - 15] >> 3);
      const std::uint32_t s1 = rotr(w[i - 2], 17) ^ rotr(w[i - 2], 19) ^ (w[i - 2] >> 10);
      w[i] = w[i - 16] + s0 + w[i - 7] + s1;
    }
    std::uint32_t a = state_[0], b = state_[1], c = state_[2], d = state_[3];
    std::uint32_t e = state_[4], f = state_[5], g = state_[6], h = state_[7];
    for (int i = 0; i < 64; ++i) {
      const std::uint32_t t1 =
          h + (rotr(e, 6) ^ rotr(e, 11) ^ rotr(e, 25)) + ((e & f) ^ (~e & g)) + k[i] + w[i];
      const std::uint32_t t2 =
          (rotr(a, 2) ^ rotr(a, 13) ^ rotr(a, 22)) + ((a & b) ^ (a & c) ^ (b & c));
      h = g;
      g = f;
      f = e;
      e = d + t1;
      d = c;
      c = b;
      b = a;
      a = t1 + t2;
    }
    state_[0] += a;
    state_[1] += b;
    state_[2] += c;
    state_[3] += d;
    state_[4] += e;
    state_[5] += f;
    state_[6] += g;
    state_[7] += h;
  }

  std::array<std::uint32_t, 8> state_{0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
                                      0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};
  std::array<unsigned char, 64> block_{};
  std::size_t used_{0};
  std::uint64_t length_{0};
};

bool is_hex_digest(const std::string& text) {
  return text.size() == 64 && std::all_of(text.begin(), text.end(), [](unsigned char c) {
           return std::isdigit(c) || (c >= 'a' && c <= 'f');
         });
}

}  // namespace

std::string sha256_hex(const std::string& bytes) {
  Sha256 hash;
  hash.update(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size());
  return hash.hex();
}

std::string sha256_file_hex(const std::filesystem::path& path) {
  // Streamed (the model is tens of MB), bounded by the model's size limit: a file that grows
  // beyond it while being hashed is refused too.
  InputFile in = open_model_file(path, kMaxModelBytes, "file listed in the checksums");
  Sha256 hash;
  std::vector<char> buffer(1 << 16);
  std::uint64_t total = 0;
  while (const std::size_t got = in.read(buffer.data(), buffer.size())) {
    total += got;
    if (total > kMaxModelBytes) {
      throw InputError(path.string(), 0, "",
                       "grew beyond " + std::to_string(kMaxModelBytes) + " bytes while hashed",
                       ExitCode::bad_model);
    }
    hash.update(reinterpret_cast<const unsigned char*>(buffer.data()), got);
  }
  return hash.hex();
}

std::filesystem::path checksum_path_of(const std::filesystem::path& model_path) {
  std::filesystem::path path = model_path;
  return path.replace_extension(".sha256");
}

int verify_model_checksums(const std::filesystem::path& checksum_file,
                           const std::filesystem::path& model_path,
                           const std::filesystem::path& anchors_path) {
  std::error_code error;
  if (!std::filesystem::exists(checksum_file, error)) return 0;
  std::istringstream in(read_model_file(checksum_file, kMaxChecksumBytes, "checksum file"));
  const std::filesystem::path folder = checksum_file.parent_path();
  int checked = 0;
  int line_number = 0;
  std::string line;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty() || line[0] == '#') continue;
    // sha256sum writes "DIGEST  NAME" (text mode) or "DIGEST *NAME" (binary mode).
    const std::string digest = line.substr(0, 64);
    if (!is_hex_digest(digest) || line.size() < 67 || line[64] != ' ' ||
        (line[65] != ' ' && line[65] != '*')) {
      throw InputError(checksum_file.string(), line_number, "",
                       "expected 'SHA256  FILE' as sha256sum writes it (run scripts/fetch_model.sh "
                       "again)",
                       ExitCode::bad_model);
    }
    const std::filesystem::path listed = folder / line.substr(66);
    for (const auto* file : {&model_path, &anchors_path}) {
      if (listed.filename() != file->filename() ||
          !std::filesystem::equivalent(listed, *file, error)) {
        continue;
      }
      const std::string actual = sha256_file_hex(*file);
      if (actual != digest) {
        throw InputError(file->string(), 0, "",
                         "checksum mismatch: " + checksum_file.string() + " line " +
                             std::to_string(line_number) + " records sha256 " + digest +
                             ", the file has " + actual +
                             " (damaged or changed: run scripts/fetch_model.sh again)",
                         ExitCode::bad_model);
      }
      ++checked;
    }
  }
  return checked;
}

}  // namespace rtmot::detector
