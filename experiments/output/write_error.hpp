// A write that failed (a full disk, a file-size limit, a closed pipe): exit 2, like bad input, with a message naming
// what could not be written and why ("cannot write OUT/bench.json: No space left on device").
#pragma once

#include <string>

#include "smithlab/errors.hpp"

namespace smithlab::output {

struct write_error : input_error {
    // `what`: the path as the user knows it, or "to standard output"; `errno_value`: the failed call's errno (0: not
    // known, said as such).
    write_error(const std::string& what, int errno_value);
};

// `path` as it is published: a stage directory's or a temporary's name (temporary_name) replaced by what it becomes,
// so that a message names OUT/bench.json, not OUT/.report.PID.smithlab-partial/bench.json.
std::string published_name(const std::string& path);

}  // namespace smithlab::output
