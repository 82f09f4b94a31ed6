/// @file
/// smithlab/util/checksum.hpp -- a text file sealed by a last line `checksum,HEX`: the CRC-64 of every byte before it.
///
/// The CRC is CRC-64/XZ (Boost.CRC: polynomial 0x42F0E1EBA9EA3693 of ECMA-182, reflected, initial value and final
/// xor all ones; the check value of "123456789" is 0x995DC9BBDF1939FA). 64 bits: every burst of up to 64 flipped
/// bits is caught, and any other change goes unseen with a chance of 2^-64 (a 32-bit CRC: 2^-32, over files that
/// may run to megabytes). The initial value of all ones makes leading zero bytes count too.
#pragma once

#include <boost/crc.hpp>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>

namespace smithlab::util {

/// The CRC-64/XZ of the file comment (Boost.CRC).
using Crc64 = boost::crc_optimal<64, 0x42F0E1EBA9EA3693ULL, ~0ULL, ~0ULL, true, true>;

/// The CRC-64/XZ of `bytes`.
inline std::uint64_t crc64(std::string_view bytes) {
    Crc64 crc;
    crc.process_bytes(bytes.data(), bytes.size());
    return crc.checksum();
}

/// The line that seals `body`: "checksum," and 16 lower-case hex digits, then a newline.
inline std::string checksum_line(std::string_view body) {
    char line[32];
    std::snprintf(line, sizeof line, "checksum,%016llx\n", static_cast<unsigned long long>(crc64(body)));
    return line;
}

/// `text` without its last line, when that line is the checksum_line of all before it; nullopt when the line is
/// missing, malformed or does not match (a file cut short, edited, or written without a seal).
inline std::optional<std::string_view> unseal(std::string_view text) {
    constexpr std::size_t line_size = 9 + 16 + 1;  // "checksum," HEX "\n"
    if (text.size() < line_size) return std::nullopt;
    const std::string_view body = text.substr(0, text.size() - line_size);
    if (!body.empty() && body.back() != '\n') return std::nullopt;
    if (text.substr(body.size()) != checksum_line(body)) return std::nullopt;
    return body;
}

}  // namespace smithlab::util
