#include "output/checked_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>

#include "output/write_error.hpp"

namespace smithlab::output {

namespace {

int open_for_writing(const std::string& path, const std::string& shown) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) throw write_error(shown, errno);
    return fd;
}

}  // namespace

CheckedFile::Buffer::Buffer(int fd_, std::string shown_) : fd(fd_), shown(std::move(shown_)) {
    setp(data_, data_ + sizeof data_);
}

void CheckedFile::Buffer::drain() {
    if (error) throw write_error(shown, error > 0 ? error : 0);
    const char* p = pbase();
    while (p < pptr()) {
        const ssize_t n = ::write(fd, p, static_cast<std::size_t>(pptr() - p));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            error = n < 0 && errno ? errno : -1;
            setp(data_, data_ + sizeof data_);  // what could not be written is dropped: the file is failed
            throw write_error(shown, error > 0 ? error : 0);
        }
        p += n;
    }
    setp(data_, data_ + sizeof data_);
}

CheckedFile::Buffer::int_type CheckedFile::Buffer::overflow(int_type c) {
    drain();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
        *pptr() = traits_type::to_char_type(c);
        pbump(1);
    }
    return traits_type::not_eof(c);
}

int CheckedFile::Buffer::sync() {
    drain();
    return 0;
}

CheckedFile::CheckedFile(int fd, std::string shown) : buffer_(fd, std::move(shown)), stream_(&buffer_) {
    stream_.exceptions(std::ios::badbit);
}

CheckedFile::CheckedFile(const std::string& path, const std::string& shown)
    : CheckedFile(open_for_writing(path, shown), shown) {}

CheckedFile::~CheckedFile() {
    if (buffer_.fd >= 0) ::close(buffer_.fd);
}

void CheckedFile::close() {
    stream_.exceptions(std::ios::goodbit);
    stream_.flush();  // a failure is in buffer_.error, thrown by drain() below
    const int fd = buffer_.fd;
    buffer_.fd = -1;
    if (buffer_.error) {
        ::close(fd);
        throw write_error(buffer_.shown, buffer_.error > 0 ? buffer_.error : 0);
    }
    if (::close(fd) != 0 && errno != EINTR) throw write_error(buffer_.shown, errno);
}

}  // namespace smithlab::output
