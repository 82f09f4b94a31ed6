// The light's direction as `trace` and `brdf` take it (and the Python module's trace and brdf): theta and phi in
// degrees, from above (theta in [0, 90)), or from below (theta in (90, 180]) for a material that transmits (the
// dielectric); never grazing. An input_error names the item (theta_name, phi_name: the option or argument).
#pragma once

#include <cmath>

#include "smithlab/errors.hpp"
#include "smithlab/geometry.hpp"
#include "smithlab/walk/facets.hpp"

namespace smithlab::trace {

inline Vec3 incident_direction(double theta, double phi, const char* theta_name, const char* phi_name,
                               const walk::Material& m) {
    if (m.transmits())
        require(theta >= 0.0 && theta <= 180.0 && theta != 90.0, theta_name, "in [0, 180] degrees, not 90 (grazing)",
                theta);
    else
        require(theta >= 0.0 && theta < 90.0, theta_name,
                "in [0, 90) degrees (light from above the surface; only a dielectric takes light from below)", theta);
    require(std::isfinite(phi), phi_name, "finite", phi);
    return direction_from_deg(theta, phi);
}

}  // namespace smithlab::trace
