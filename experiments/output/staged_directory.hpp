// A directory of outputs (the report's) built aside and moved in when complete: a run that fails or is killed
// leaves the previous contents as they were, never a truncated file.
//
// The stage is OUT/.report.PID.smithlab-partial; publish() renames each file into OUT (each rename is atomic, so
// a reader sees every file either old or new and whole), then removes the stage. A signal removes the stage
// (signal_cleanup.hpp); a SIGKILL's stage is removed by the next run into OUT.
#pragma once

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "output/signal_cleanup.hpp"

namespace smithlab::output {

class StagedDirectory {
public:
    // Refuses `out` unless it is a directory or absent (input_error); creates it and the stage.
    StagedDirectory(const std::filesystem::path& out, const std::string& name);
    ~StagedDirectory();  // unless published: removes the stage, and the directories it created if they stayed empty
    StagedDirectory(const StagedDirectory&) = delete;
    StagedDirectory& operator=(const StagedDirectory&) = delete;

    const std::filesystem::path& path() const { return stage_->path(); }  // write everything here
    void publish();

private:
    std::filesystem::path out_;
    std::optional<Temporary> stage_;
    std::vector<std::filesystem::path> created_;  // out and the parents it had to create, innermost first
};

// Closes a file written into the stage and refuses to go on when any write to it failed (a full disk, a file-size
// limit): the stage is then never published. Throws write_error naming the file as published (OUT/NAME).
void finish(std::ofstream& out, const std::filesystem::path& path);
// Writes `text` to a new file of the stage, checked as finish() does.
void write_file(const std::filesystem::path& path, const std::string& text);

// `out` as a directory to write into: absent (then the nearest existing directory above it must be writable) or a
// writable directory (unwritable(): read-only by its mode bits is refused, for root too); a dangling symbolic link is
// refused, naming its target. Throws input_error naming `out`.
void require_output_directory(const std::filesystem::path& out);

}  // namespace smithlab::output
