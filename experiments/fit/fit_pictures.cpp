#include "fit_pictures.hpp"

namespace smithlab::fitrun {

std::string write_pictures(const std::filesystem::path&, const FitScene&, const Results&, const NdfRegistry&, unsigned) {
    return "";  // placeholder (issue 12)
}

}  // namespace smithlab::fitrun
