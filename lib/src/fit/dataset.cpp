// placeholder (issue 12)
#include "smithlab/fit/dataset.hpp"
