#pragma once
// The one RAII output file of rtmot (results, message files, reports, tables). Written in whole
// records: a record is buffered whole and the buffer reaches the disk only at record boundaries,
// in one write() (a record above the buffer's size goes out in one write() of its own), and a
// failed write (disk full) is cut back to the last whole record. A process killed (SIGKILL, or
// the second stop signal's immediate exit) while that write() copies can leave one torn record
// at the end: the kernel stops a write between two pages of the file, so such a cut lies at a
// 4096-byte boundary and only at the end; readers report it as a record cut at the end
// (MessageFileReader: broken_framing, "cut after"), and a reader of JSON lines drops an
// unterminated last line. Nothing before it is ever torn. A file can also appear only once
// complete: written to a temporary beside it and renamed by close(), so a stopped or killed program
// leaves the old file or the new one, never a part.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

namespace rtmot {

class OutputFile {
 public:
  enum class Publish {
    as_written,  // PATH itself, created or truncated now (streams: messages, JSON lines),
                 // locked while written (common/output_open.hpp)
    appended,    // PATH itself, written after what it holds (a log), not locked
    on_close,    // PATH appears at close(), whole; until then PATH.tmp-<pid>; temporaries of
                 // writers that no longer run are removed first (common/stale_temporaries.hpp)
  };

  /// Throws InputError (bad_input) naming `path` if it cannot be created, or is a FIFO no process
  /// reads, a folder, socket or block device, or a file another process is writing
  /// (common/output_open.hpp: where every output is opened).
  explicit OutputFile(std::filesystem::path path, Publish publish = Publish::as_written,
                      std::size_t buffer_bytes = 64 * 1024);
  /// Without close(): an `as_written` file gets its whole buffered records and is closed (errors
  /// cannot be reported here: call flush() or close() to know); an `on_close` temporary is
  /// removed, PATH is left as it was.
  ~OutputFile();
  OutputFile(OutputFile&& other) noexcept;
  OutputFile& operator=(OutputFile&&) = delete;
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// Appends one whole record. Throws InputError (io_error) naming the file if writing failed;
  /// the file then ends with the last whole record.
  void write(const void* data, std::size_t size);
  void write(std::string_view text) { write(text.data(), text.size()); }
  /// Hands every buffered record to the kernel; throws as write().
  void flush();
  /// Flushes, closes and (on_close) publishes PATH; throws as write(). Idempotent.
  void close() {
    finish_writing();
    publish();
  }
  /// close() in two steps, for files published together (publish_together()): everything that
  /// can fail for the disk (flush, fsync, close), then the rename. Both idempotent.
  void finish_writing();
  void publish();

  const std::filesystem::path& path() const { return path_; }

 private:
  /// Writes `size` bytes; on failure cuts the file back to the end of the last whole record,
  /// `record_ends` (ascending offsets in `data`) telling where records end.
  void write_out(const char* data, std::size_t size, const std::vector<std::size_t>& record_ends);
  [[noreturn]] void fail(const char* action, int error);

  std::filesystem::path path_;
  std::filesystem::path written_path_;  // path_, or the temporary
  Publish publish_;
  int fd_{-1};
  bool unpublished_{false};  // finish_writing() done, publish() not yet (on_close)
  std::vector<char> buffer_;
  std::size_t used_{0};
  std::vector<std::size_t> record_ends_;  // in buffer_: where each buffered record ends
};

/// Writes `text` to `path` as one record, published on close (never a partial file).
void write_whole_file(const std::filesystem::path& path, std::string_view text);

/// Publishes files that belong together (a results file and its list of processed frames) both
/// or neither: each is finished (a full disk fails here, before any is renamed), then each is
/// published. Throws as close(); what was not published is removed by its destructor.
void publish_together(OutputFile& first, OutputFile& second);

}  // namespace rtmot
