#include "output/write_error.hpp"

#include <cstring>
#include <filesystem>
#include <iterator>

namespace smithlab::output {

namespace {

std::string reason(int errno_value) {
    return errno_value ? std::strerror(errno_value) : "a write failed (disk full or file too large?)";
}

// ".NAME.PID.smithlab-partial" -> NAME; anything else -> empty.
std::string temporary_of(const std::string& part) {
    constexpr std::string_view suffix = ".smithlab-partial";
    if (part.size() <= suffix.size() + 2 || part[0] != '.' || !part.ends_with(suffix)) return {};
    const std::string inner = part.substr(1, part.size() - suffix.size() - 1);  // NAME.PID
    const std::size_t dot = inner.rfind('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == inner.size() ||
        inner.find_first_not_of("0123456789", dot + 1) != std::string::npos)
        return {};
    return inner.substr(0, dot);
}

}  // namespace

write_error::write_error(const std::string& what, int errno_value)
    : input_error("cannot write " + what + ": " + reason(errno_value)) {}

std::string published_name(const std::string& path) {
    const std::filesystem::path p(path);
    std::filesystem::path shown;
    for (auto it = p.begin(); it != p.end(); ++it) {
        const std::string name = temporary_of(it->string());
        if (name.empty()) shown /= *it;
        else if (std::next(it) == p.end()) shown /= name;  // a file's temporary: the file it becomes
        // else a stage directory inside OUT: its files land in OUT itself
    }
    return shown.string();
}

}  // namespace smithlab::output
