// Where a command's output goes, decided before any work is done, and written so that nothing half-written is
// ever left there.
//
//   absent, or a regular file (through any symlinks: the link's target is written, the link kept)
//       -> written to a temporary beside it, ".NAME.PID.smithlab-partial", renamed into place when complete;
//          the file's permissions are kept. A read-only file, or a file in a read-only directory, is refused, not
//          replaced: read-only by its mode bits, for root too (root may write anything; the bits say what the
//          owner meant).
//   a character device or a FIFO (/dev/null, /dev/stdout, a pipe)
//       -> written straight to it: there is nothing to replace. A FIFO is opened when resolved: one with no reader
//          is refused (a write to it would wait forever).
//   anything else (a directory, a socket, a block device), or an input of the same run
//       -> refused, naming the path (input_error: exit 2).
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace smithlab::output {

struct OutputTarget {
    std::filesystem::path path;       // symlinks resolved
    bool streamed = false;            // a character device or FIFO: written in place
    std::string shown;                // the path as the user gave it, for messages
    std::shared_ptr<const int> fifo;  // a FIFO's descriptor, opened by resolve_output (its reader is there)
};

// Checks `path` as an output of a run that reads `inputs`; throws input_error naming what is wrong.
OutputTarget resolve_output(const std::string& path, const std::vector<std::string>& inputs = {});

// Writes through `write` as described above; when `write` throws, nothing is left and the exception goes on. Every
// write is checked (checked_file.hpp): the first that fails stops `write` with write_error naming the output.
void write_output(const OutputTarget& target, const std::function<void(std::ostream&)>& write);
void write_output(const OutputTarget& target, const std::string& text);

// The temporary name of `name` for this process.
std::string temporary_name(const std::string& name);
// Removes, in `dir`, the temporaries of `name` left by processes that no longer run (a SIGKILL's debris).
void remove_stale_temporaries(const std::filesystem::path& dir, const std::string& name);

// Why `p` (an existing file or directory) cannot be written into, or empty: "is read-only" by its mode bits, for root
// too (root may write anything; the bits say whether the owner meant it to be written), else access(2)'s answer.
std::string unwritable(const std::filesystem::path& p);

// An input file that can be read: it exists and is not a directory. Throws input_error naming `what` and the path.
void require_readable_input(const std::string& path, const std::string& what);

}  // namespace smithlab::output
