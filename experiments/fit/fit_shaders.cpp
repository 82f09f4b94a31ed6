#include "fit_shaders.hpp"

namespace smithlab::fitrun {

void write_shaders(const std::filesystem::path&, const Results&) {}  // placeholder: being written (issue 12)

}  // namespace smithlab::fitrun
