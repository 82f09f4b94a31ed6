/// @file
/// smithlab/named.hpp -- enumerators by name: one table per enum, read by its parser, its printer and the CLI's help.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace smithlab {

/// One enumerator of E with its name (as parsed and printed) and a one-line description (for the CLI's help).
template <class E>
struct Named {
    /// The enumerator.
    E value;
    /// Its name, and what it means.
    /// @{
    std::string_view name, description;
    /// @}
};

/// The entry named `name`, or nullptr.
template <class E, std::size_t N>
constexpr const Named<E>* find_named(const std::array<Named<E>, N>& table, std::string_view name) {
    for (const Named<E>& e : table)
        if (e.name == name) return &e;
    return nullptr;
}

/// show(entry) for each entry, joined by sep, the last by last_sep: "a, b or c" with sep ", " and last_sep " or ".
template <class E, std::size_t N, class Show>
std::string join_entries(const std::array<Named<E>, N>& table, std::string_view sep, std::string_view last_sep,
                         const Show& show) {
    std::string out;
    for (std::size_t i = 0; i < N; ++i) {
        if (i > 0) out += i + 1 == N ? last_sep : sep;
        out += show(table[i]);
    }
    return out;
}

/// The names joined by sep, the last by last_sep: "a, b or c" with sep ", " and last_sep " or ".
template <class E, std::size_t N>
std::string join_names(const std::array<Named<E>, N>& table, std::string_view sep, std::string_view last_sep) {
    return join_entries(table, sep, last_sep, [](const Named<E>& e) { return std::string(e.name); });
}

/// "name (description)" for each entry, joined as join_names joins the names (for a CLI option's help).
template <class E, std::size_t N>
std::string join_described(const std::array<Named<E>, N>& table, std::string_view sep, std::string_view last_sep) {
    return join_entries(table, sep, last_sep, [](const Named<E>& e) {
        return std::string(e.name) + " (" + std::string(e.description) + ")";
    });
}

/// Every name of the table, in its order (for a CLI's list of accepted values).
template <class E, std::size_t N>
std::vector<std::string> names_of(const std::array<Named<E>, N>& table) {
    std::vector<std::string> out;
    for (const Named<E>& e : table) out.emplace_back(e.name);
    return out;
}

/// The name of value in table, or "?".
template <class E, std::size_t N>
constexpr std::string_view name_of(const std::array<Named<E>, N>& table, E value) {
    for (const Named<E>& e : table)
        if (e.value == value) return e.name;
    return "?";
}

}  // namespace smithlab
