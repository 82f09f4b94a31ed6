// Catch2 v2 needs one translation unit with its main(); this is it.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
