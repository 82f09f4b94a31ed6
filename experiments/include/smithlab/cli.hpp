/// @file
/// <smithlab/cli.hpp> -- the `smithlab` command line as a library call (target smithlab::cli).
///
/// A program that registers its own NDFs becomes a full `smithlab` with them: eval, check, sample, report, trace,
/// brdf, fit and list, each NDF walked and fitted as its own type (registry.hpp, surface.hpp):
///     int main(int argc, char** argv) {
///         smithlab::NdfRegistry registry = smithlab::builtin_registry();
///         registry.add({.name = "mine", .parameters = {"alpha"}, .description = "...",
///                       .examples = {"mine(alpha=0.3)"}},
///                      [](const smithlab::NdfParams& p) { return Mine{p.at("alpha")}; });
///         return smithlab::run_cli(argc, argv, registry);
///     }
/// Its `--help` names the registry's NDFs, its own among them; `--version` prints smithlab's version. Its own facet
/// materials and diffuse models come in the same way, added to `registry.materials()` and
/// `registry.diffuse_models()` (docs/extending.md).
/// Under mpirun (where the library was built with MPI), trace, fit and report run on every rank, as `smithlab` does.
#pragma once

#include "smithlab/registry.hpp"

namespace smithlab {

/// Parses argv as `smithlab` does and runs the subcommand on `registry`; returns the exit code (0 fine, 1 a check
/// failed, 2 bad input, 3 an internal error). Call it once, from main, before any other thread starts: it installs
/// the signal handlers that remove a run's temporary outputs, and initializes MPI under mpirun.
int run_cli(int argc, char** argv, const NdfRegistry& registry);

}  // namespace smithlab
