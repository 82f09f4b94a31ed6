// smithlab -- the command line on the built-in NDFs (smithlab/cli.hpp: a program of one's own adds its NDFs first).
#include "smithlab/cli.hpp"
#include "smithlab/gtr/registry.hpp"

int main(int argc, char** argv) { return smithlab::run_cli(argc, argv, smithlab::builtin_registry()); }
