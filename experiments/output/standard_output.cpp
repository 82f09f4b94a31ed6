#include "output/standard_output.hpp"

#include <cerrno>
#include <cstdio>
#include <iostream>

#include "output/write_error.hpp"

namespace smithlab::output {

namespace {

[[noreturn]] void failed(int errno_value) { throw write_error("to standard output", errno_value); }

}  // namespace

StandardOutput::Buffer::int_type StandardOutput::Buffer::overflow(int_type c) {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    errno = 0;
    if (std::putc(traits_type::to_char_type(c), stdout) == EOF) failed(errno);
    return c;
}

std::streamsize StandardOutput::Buffer::xsputn(const char* s, std::streamsize n) {
    errno = 0;
    if (std::fwrite(s, 1, static_cast<std::size_t>(n), stdout) != static_cast<std::size_t>(n)) failed(errno);
    return n;
}

// Never throws: std::cerr flushes std::cout before each message (tie), the message of a failed write included. A
// failure stays in ferror(stdout), for check_standard_output().
int StandardOutput::Buffer::sync() {
    std::fflush(stdout);
    return 0;
}

StandardOutput::StandardOutput() : previous_(std::cout.rdbuf(&buffer_)) { std::cout.exceptions(std::ios::badbit); }

void StandardOutput::quiet() { std::cout.exceptions(std::ios::goodbit); }

StandardOutput::~StandardOutput() {
    quiet();
    std::cout.clear();
    std::cout.rdbuf(previous_);
}

void check_standard_output() {
    errno = 0;
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) failed(errno);
}

}  // namespace smithlab::output
