// A progress line with an ETA on stderr for long runs: none in the first 3 s, then at most one every 2 s, none at 0 or
// at the end. The caller gives the fraction done and the line's text (built only when a line is due).
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace smithlab::output {

class ProgressLine {
public:
    // Prints "TEXT, N s elapsed, ETA M s" when due; text() -> std::string.
    template <class Text>
    void operator()(double fraction, Text&& text) {
        const auto now = std::chrono::steady_clock::now();
        const double t = std::chrono::duration<double>(now - start_).count();
        if (t < 3.0 || std::chrono::duration<double>(now - last_).count() < 2.0 || !(fraction > 0.0) || fraction >= 1.0)
            return;
        last_ = now;
        std::fprintf(stderr, "%s, %.0f s elapsed, ETA %.0f s\n", std::string(text()).c_str(), t,
                     t * (1.0 - fraction) / fraction);
    }

private:
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_ = start_;
};

}  // namespace smithlab::output
