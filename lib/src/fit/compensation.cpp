// placeholder: filled in by the compensation work of issue 12
#include "smithlab/fit/compensation.hpp"
