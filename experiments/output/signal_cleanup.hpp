// Temporary files and directories that a signal must not leave behind.
//
// A command writes its outputs to temporaries and renames them into place (output_file.hpp). SIGINT, SIGTERM and
// SIGHUP are taken by one thread that waits for them (sigwait, so the cleanup runs in an ordinary context, not in
// a signal handler): it removes every temporary still registered, then lets the signal end the process as it
// would have. A SIGKILL cannot be caught; the temporaries' names say which process made them, and the next run
// that writes to the same place removes those of dead processes (remove_stale_temporaries).
//
// The one piece of process-wide state in smithlab: signals are process-wide.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace smithlab::output {

// Call first thing in main(), before any other thread exists (they inherit the blocked signal mask).
void install_signal_cleanup();

// Registers `path` for removal (file or directory tree) if a signal ends the process while this object lives.
class Temporary {
public:
    explicit Temporary(std::filesystem::path path);
    ~Temporary();
    Temporary(const Temporary&) = delete;
    Temporary& operator=(const Temporary&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

// While it lives, note() is printed to stderr when a signal ends the process, before the cleanup: what the run held
// when it was stopped (a distributed run's rank 0 says which rank held which work when mpirun ends the job because
// a rank died). note() runs on the signal thread: it locks what it reads.
class SignalNote {
public:
    explicit SignalNote(std::function<std::string()> note);
    ~SignalNote();
    SignalNote(const SignalNote&) = delete;
    SignalNote& operator=(const SignalNote&) = delete;

private:
    std::function<std::string()> note_;
};

// Ends the process as `signal` would, after the cleanup: for a child process that a signal stopped (the user's
// Ctrl-C reaches the whole process group, and std::system ignores SIGINT in the parent meanwhile).
[[noreturn]] void end_as_signalled(int signal);

}  // namespace smithlab::output
