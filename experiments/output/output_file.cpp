#include "output/output_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <memory>

#include "output/checked_file.hpp"
#include "output/signal_cleanup.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::output {

namespace fs = std::filesystem;

namespace {

constexpr const char* suffix = ".smithlab-partial";

[[noreturn]] void refuse(const std::string& shown, const std::string& why) {
    throw input_error("output '" + shown + "': " + why);
}

// Follows symlinks one link at a time (a dangling link names the file to create); refuses a loop.
fs::path follow_links(fs::path p, const std::string& shown) {
    for (int hops = 0; fs::is_symlink(fs::symlink_status(p)); ++hops) {
        if (hops == 40) refuse(shown, "too many levels of symbolic links");
        const fs::path target = fs::read_symlink(p);
        p = target.is_absolute() ? target : p.parent_path() / target;
    }
    return p;
}

bool same_file(const fs::path& a, const std::string& b) {
    std::error_code ec;
    return fs::exists(b, ec) && fs::equivalent(a, b, ec);
}

}  // namespace

std::string unwritable(const fs::path& p) {
    struct stat st {};
    if (::stat(p.c_str(), &st) != 0) return std::string("cannot be examined: ") + std::strerror(errno);
    if ((st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0) return "is read-only";
    if (::access(p.c_str(), W_OK) != 0) return std::string("is not writable: ") + std::strerror(errno);
    return {};
}

namespace {

// A FIFO opened now, before any work: without a reader, open(2) would wait for one forever (refused instead); with
// one, the descriptor is held until the write, so that the reader does not see an end of file in between.
std::shared_ptr<const int> open_fifo(const fs::path& p, const std::string& shown) {
    const int fd = ::open(p.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0 && errno == ENXIO) refuse(shown, "is a FIFO with no reader (start the reader first)");
    if (fd < 0) refuse(shown, std::string("cannot be opened: ") + std::strerror(errno));
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);  // the writes wait for the reader as usual
    return std::shared_ptr<const int>(new int(fd), [](const int* f) {
        ::close(*f);
        delete f;
    });
}

// A descriptor for writing to a character device or a FIFO (a duplicate of the FIFO's, which stays open).
int open_streamed(const OutputTarget& t) {
    const int fd = t.fifo ? ::fcntl(*t.fifo, F_DUPFD_CLOEXEC, 0) : ::open(t.path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) refuse(t.shown, std::string("cannot be opened: ") + std::strerror(errno));
    return fd;
}

}  // namespace

std::string temporary_name(const std::string& name) { return "." + name + "." + std::to_string(::getpid()) + suffix; }

void remove_stale_temporaries(const fs::path& dir, const std::string& name) {
    std::error_code ec;
    const std::string prefix = "." + name + ".";
    for (const auto& entry : fs::directory_iterator(dir.empty() ? "." : dir, ec)) {
        const std::string f = entry.path().filename().string();
        if (f.size() <= prefix.size() + std::strlen(suffix) || f.rfind(prefix, 0) != 0 || !f.ends_with(suffix))
            continue;
        const std::string pid = f.substr(prefix.size(), f.size() - prefix.size() - std::strlen(suffix));
        if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) continue;
        const pid_t p = static_cast<pid_t>(std::stol(pid));
        if (p == ::getpid() || ::kill(p, 0) == 0 || errno != ESRCH) continue;  // its maker still runs
        std::error_code ignored;
        fs::remove_all(entry.path(), ignored);
    }
}

OutputTarget resolve_output(const std::string& path, const std::vector<std::string>& inputs) {
    if (path.empty()) refuse(path, "empty path");
    std::error_code ec;
    // A device or a FIFO as the kernel resolves it (/dev/stdout onto a pipe: a link /proc/self/fd/1 -> "pipe:[N]",
    // which follow_links would take for a dangling link to a file to create) is written through the path as given.
    switch (fs::status(path, ec).type()) {
        case fs::file_type::character:
            return {path, true, path, nullptr};
        case fs::file_type::fifo:
            return {path, true, path, open_fifo(path, path)};
        default:
            break;
    }
    const fs::path p = follow_links(path, path);
    for (const std::string& in : inputs)
        if (same_file(p, in)) refuse(path, "is the input file '" + in + "'; it would be overwritten");
    const fs::file_status st = fs::status(p, ec);
    switch (st.type()) {
        case fs::file_type::not_found:
        case fs::file_type::regular: {
            const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
            if (!fs::is_directory(dir)) refuse(path, "its directory '" + dir.string() + "' does not exist");
            if (st.type() == fs::file_type::regular && !unwritable(p).empty())
                refuse(path, unwritable(p) + "; not replaced");
            if (const std::string why = unwritable(dir); !why.empty())
                refuse(path, "its directory '" + dir.string() + "' " + why);
            return {p, false, path, nullptr};
        }
        case fs::file_type::directory:
            refuse(path, "is a directory");
        default:
            refuse(path, "is not a regular file, a character device or a FIFO");
    }
}

void write_output(const OutputTarget& t, const std::function<void(std::ostream&)>& write) {
    if (t.streamed) {
        CheckedFile out(open_streamed(t), t.shown);
        write(out.stream());
        out.close();
        return;
    }
    const fs::path dir = t.path.parent_path();
    const std::string name = t.path.filename().string();
    remove_stale_temporaries(dir, name);
    const Temporary tmp(dir / temporary_name(name));
    try {
        CheckedFile out(tmp.path().string(), t.shown);
        write(out.stream());
        out.close();
        std::error_code ec;
        if (fs::exists(t.path)) fs::permissions(tmp.path(), fs::status(t.path).permissions(), ec);
        fs::rename(tmp.path(), t.path, ec);
        if (ec) refuse(t.shown, "cannot be replaced: " + ec.message());
    } catch (...) {
        std::error_code ignored;
        fs::remove(tmp.path(), ignored);
        throw;
    }
}

void write_output(const OutputTarget& t, const std::string& text) {
    write_output(t, [&](std::ostream& out) { out << text; });
}

void require_readable_input(const std::string& path, const std::string& what) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (st.type() == fs::file_type::not_found) throw input_error(what + " '" + path + "' does not exist");
    if (st.type() == fs::file_type::directory) throw input_error(what + " '" + path + "' is a directory");
    if (::access(path.c_str(), R_OK) != 0)
        throw input_error(what + " '" + path + "' cannot be read: " + std::strerror(errno));
}

}  // namespace smithlab::output
