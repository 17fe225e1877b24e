#include "detector/model_files.hpp"

#include "common/input_error.hpp"

namespace rtmot::detector {
namespace {

// InputFile says what is wrong with the path (bad_input); for the model's files the exit code is
// the model's, and the way out is fetching it again.
[[noreturn]] void rethrow_as_model_error(const InputError& e, const std::string& what,
                                         const std::string& remedy = "run scripts/fetch_model.sh") {
  if (e.exit_code() != ExitCode::bad_input) throw e;  // io_error: a read error stays one
  throw InputError(e.file(), e.line(), e.field(),
                   std::string(e.what()).substr(e.file().empty() ? 0 : e.file().size() + 2) +
                       " (the " + what + "; " + remedy + ")",
                   ExitCode::bad_model);
}

}  // namespace

std::string read_model_file(const std::filesystem::path& path, std::uint64_t max_bytes,
                            const std::string& what, const std::string& remedy) {
  try {
    return read_text_file(path, max_bytes);
  } catch (const InputError& e) {
    rethrow_as_model_error(e, what, remedy);
  }
}

InputFile open_model_file(const std::filesystem::path& path, std::uint64_t max_bytes,
                          const std::string& what) {
  try {
    return InputFile(path, max_bytes);
  } catch (const InputError& e) {
    rethrow_as_model_error(e, what);
  }
}

}  // namespace rtmot::detector
