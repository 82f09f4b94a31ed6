#include "smithlab/surface.hpp"

namespace smithlab {

std::shared_ptr<const AnySurface> make_surface(const AnyNdf& ndf, const walk::MicrosurfaceOptions& opts) {
    if (ndf.kernels()) return ndf.kernels()->surface(ndf, opts);
    return std::make_shared<const SurfaceOf<AnyNdf>>(ndf, opts, ndf);
}

}  // namespace smithlab
