// placeholder: filled in by issue 9 work
#include <catch2/catch.hpp>
