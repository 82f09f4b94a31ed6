// placeholder: filled in by the diffuse_models work of issue 12
#include "smithlab/fit/diffuse_models.hpp"
