#pragma once
// Where every output file of rtmot is opened: common/output_file.hpp (results, message files,
// reports, tables, the log file) and the annotated video's file (outputs/video_target.cpp,
// outputs/gst_video_output.cpp). Two ways, one rule each:
//
// - PATH itself (a stream of messages, a log, or a device or FIFO named as an output) is opened
//   without blocking: a FIFO that no process reads is refused at once ("a FIFO with no reader"),
//   where open() used to wait for a reader forever, deaf to SIGTERM. A folder, socket or block
//   device is refused with its kind. A regular file that is truncated is locked first (flock, an
//   advisory lock held while it is written): a second rtmot writing the same file is refused
//   instead of interleaving its records with the first's; appending (the log) takes no lock.
// - A temporary, PATH.tmp-PID (outputs published whole on close), is created exclusively and
//   never through a symbolic link (O_CREAT | O_EXCL | O_NOFOLLOW): a link or file planted under
//   that name is never written through or truncated. The name holds this process's id, so what is
//   already there is no running writer's: it was left by an earlier process with the same id (in
//   a container, every start has the same id) or planted. Its name is removed (a link is removed,
//   not followed; a hard link's other names keep their content), with a warning, and the
//   temporary created anew; what cannot be removed (a folder) is refused.
#include <filesystem>

namespace rtmot {

enum class OutputMode {
  truncate,  // a new file, or an existing one emptied (after its lock is taken)
  append,    // written after what is there (a log: several writers append whole lines)
};

/// Opens PATH itself for writing (blocking writes, close-on-exec) and returns the descriptor,
/// which the caller owns. Throws InputError (bad_input) naming PATH and why: it cannot be
/// created, is a folder, a socket or a block device, a FIFO with no reader, or (truncate) a file
/// another process holds locked.
int open_output_in_place(const std::filesystem::path& path, OutputMode mode);

/// Removes the stale temporaries of PATH (common/stale_temporaries.hpp), creates
/// temporary_path_for(PATH) exclusively and returns its descriptor (the caller owns it). Throws
/// InputError (bad_input) naming PATH when it cannot.
int create_temporary(const std::filesystem::path& path);

}  // namespace rtmot
