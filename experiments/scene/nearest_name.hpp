// The nearest of a list of names to a misspelt one, for "did you mean ...?" in the messages that refuse an unknown
// key (strict_table.hpp).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace smithlab::scene {

// Edit distance with adjacent transpositions (optimal string alignment): insertions, deletions, substitutions and
// swaps of two neighbours count 1 each ("titel" -> "title" is 1).
std::size_t edit_distance(std::string_view a, std::string_view b);

// The name of `known` nearest to `name`, or "" when none is near enough to be a misspelling of it (a distance of
// at most a third of the longer name, and at least 1 allowed).
std::string nearest_name(std::string_view name, const std::vector<std::string>& known);

}  // namespace smithlab::scene
