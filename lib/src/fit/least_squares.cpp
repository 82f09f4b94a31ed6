// placeholder (issue 12)
#include "smithlab/fit/least_squares.hpp"
