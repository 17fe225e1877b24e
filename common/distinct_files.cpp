#include "common/distinct_files.hpp"

#include <sys/stat.h>

#include <optional>

#include "common/input_error.hpp"

namespace rtmot {
namespace {

// What makes two names one file: (device, inode) when it exists, else its resolved path.
struct Identity {
  bool exists{false};
  dev_t device{0};
  ino_t inode{0};
  std::string resolved;

  bool operator==(const Identity& other) const {
    if (exists != other.exists) return false;
    return exists ? device == other.device && inode == other.inode : resolved == other.resolved;
  }
};

Identity identity_of(const std::filesystem::path& path) {
  Identity identity;
  struct stat status {};
  if (::stat(path.c_str(), &status) == 0) {  // follows symbolic links
    identity.exists = true;
    identity.device = status.st_dev;
    identity.inode = status.st_ino;
    return identity;
  }
  std::error_code error;
  const auto absolute = std::filesystem::absolute(path, error);
  const auto resolved = std::filesystem::weakly_canonical(error ? path : absolute, error);
  identity.resolved = (error ? path : resolved).lexically_normal().string();
  return identity;
}

struct Named {
  const NamedFile* file;
  Identity identity;
};

std::vector<Named> identities(const std::vector<NamedFile>& files) {
  std::vector<Named> named;
  for (const auto& file : files) {
    if (!file.path.empty()) named.push_back({&file, identity_of(file.path)});
  }
  return named;
}

std::string describe(const NamedFile& file) {
  return file.named_by + " '" + file.path.string() + "'";
}

}  // namespace

void check_distinct_files(const std::vector<NamedFile>& inputs,
                          const std::vector<NamedFile>& outputs) {
  const std::vector<Named> read = identities(inputs);
  const std::vector<Named> written = identities(outputs);
  for (std::size_t i = 0; i < written.size(); ++i) {
    const NamedFile& output = *written[i].file;
    for (const auto& input : read) {
      if (written[i].identity == input.identity) {
        throw InputError(output.path.string(), 0, output.named_by,
                         "is the same file as the input " + describe(*input.file) +
                             ": writing it would destroy what is read");
      }
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (written[i].identity == written[j].identity) {
        throw InputError(output.path.string(), 0, output.named_by,
                         "is the same file as the output " + describe(*written[j].file) +
                             ": one would overwrite the other");
      }
    }
  }
}

}  // namespace rtmot
