// Standard output, checked: a command's results are worth nothing when they did not arrive (a full disk, a file-size
// limit, a closed pipe). While a StandardOutput lives, std::cout writes through stdio's stdout (the order of cout
// and printf output is kept) and the first failed write throws write_error("to standard output"), so that a long
// stream stops at once; check_standard_output() flushes and reports a failure of either, printf's included.
#pragma once

#include <ostream>
#include <streambuf>

namespace smithlab::output {

class StandardOutput {
public:
    StandardOutput();
    ~StandardOutput();  // std::cout as it was
    StandardOutput(const StandardOutput&) = delete;
    StandardOutput& operator=(const StandardOutput&) = delete;
    // std::cout throws no more (a failure stays for check_standard_output): call it before a message goes to
    // std::cerr, which flushes std::cout first.
    void quiet();

private:
    class Buffer : public std::streambuf {
    protected:
        int_type overflow(int_type c) override;
        std::streamsize xsputn(const char* s, std::streamsize n) override;
        int sync() override;
    };
    Buffer buffer_;
    std::streambuf* previous_;
};

// Flushes stdout; throws write_error("to standard output") when this or any write before it failed.
void check_standard_output();

}  // namespace smithlab::output
