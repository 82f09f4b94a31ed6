// An output stream over a file descriptor whose every write is checked. The first write that fails throws
// write_error naming the file, so that a long stream stops at once; close() reports a write or a close that failed.
#pragma once

#include <ostream>
#include <streambuf>
#include <string>

namespace smithlab::output {

class CheckedFile {
public:
    // Takes `fd` (open for writing); `shown` names the file in messages.
    CheckedFile(int fd, std::string shown);
    // Opens `path` for writing, created or truncated (mode 0666 less the umask); throws write_error when it cannot.
    CheckedFile(const std::string& path, const std::string& shown);
    ~CheckedFile();  // closes without flushing when close() was not called: an exception is on its way
    CheckedFile(const CheckedFile&) = delete;
    CheckedFile& operator=(const CheckedFile&) = delete;

    // Throws write_error at a failed write. stream().exceptions(std::ios::goodbit) makes it only record the failure
    // (for a writer that must not see an exception, such as Google Benchmark's reporter); close() then throws.
    std::ostream& stream() { return stream_; }
    void close();

private:
    class Buffer : public std::streambuf {
    public:
        Buffer(int fd, std::string shown);
        void drain();  // writes what is buffered; throws write_error when that fails, or failed before
        int fd = -1;
        int error = 0;  // errno of the first failed write (-1: failed, errno unknown)
        std::string shown;

    protected:
        int_type overflow(int_type c) override;
        int sync() override;

    private:
        char data_[1 << 16];
    };
    Buffer buffer_;
    std::ostream stream_;
};

}  // namespace smithlab::output
