#include "output/signal_cleanup.hpp"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <set>
#include <system_error>
#include <thread>
#include <vector>

namespace smithlab::output {

namespace fs = std::filesystem;

namespace {

struct Registry {
    std::mutex mutex;
    std::multiset<fs::path> paths;
    // Apart from the paths' mutex: a note locks what it reads, and that owner may register a temporary meanwhile.
    std::mutex notes_mutex;
    std::vector<const std::function<std::string()>*> notes;
};

Registry& registry() {
    static Registry r;
    return r;
}

sigset_t cleanup_signals() {
    sigset_t set;
    sigemptyset(&set);
    for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&set, s);
    return set;
}

}  // namespace

void install_signal_cleanup() {
    const sigset_t set = cleanup_signals();
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
    std::thread([set] {
        int sig = SIGTERM;
        sigwait(&set, &sig);
        Registry& r = registry();
        {
            const std::lock_guard lock(r.notes_mutex);
            for (const auto* note : r.notes) {
                const std::string text = (*note)();
                if (!text.empty()) std::fprintf(stderr, "%s\n", text.c_str());
            }
        }
        {
            const std::lock_guard lock(r.mutex);  // held until the end: no temporary is renamed meanwhile
            for (const fs::path& p : r.paths) {
                std::error_code ignored;
                fs::remove_all(p, ignored);
            }
            signal(sig, SIG_DFL);
            pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
            raise(sig);
            _exit(128 + sig);
        }
    }).detach();
}

void end_as_signalled(int sig) {
    kill(getpid(), sig);  // to the process: the waiting thread takes it, cleans up and ends the process
    for (;;) pause();
}

SignalNote::SignalNote(std::function<std::string()> note) : note_(std::move(note)) {
    Registry& r = registry();
    const std::lock_guard lock(r.notes_mutex);
    r.notes.push_back(&note_);
}

SignalNote::~SignalNote() {
    Registry& r = registry();
    const std::lock_guard lock(r.notes_mutex);
    r.notes.erase(std::find(r.notes.begin(), r.notes.end(), &note_));
}

Temporary::Temporary(fs::path path) : path_(std::move(path)) {
    Registry& r = registry();
    const std::lock_guard lock(r.mutex);
    r.paths.insert(path_);
}

Temporary::~Temporary() {
    Registry& r = registry();
    const std::lock_guard lock(r.mutex);
    r.paths.erase(r.paths.find(path_));
}

}  // namespace smithlab::output
