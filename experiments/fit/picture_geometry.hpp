// The geometry of the fit's pictures (fit/fit_pictures.hpp): the lit spheres' pixels as Hammon 2017 laid them out,
// and Burley 2012's BRDF slices, as pairs of directions in the macrosurface's frame.
#pragma once

#include <cstddef>
#include <vector>

#include "smithlab/geometry.hpp"

namespace smithlab::fit {

// Hammon 2017, slides "Direct only" ... "Approximate diffuse only" (shared/refs, lines 700-760 and 1715-1755): rows
// the light at 0, 90 and 135 degrees from the viewer, each row three spheres at albedo 0.75, 0.5, 0.25.
inline constexpr double light_degrees[] = {0.0, 90.0, 135.0};
inline constexpr double sphere_albedos[] = {0.75, 0.5, 0.25};
inline constexpr double slice_albedo = 0.75;

// A point to trace, in the macrosurface's frame: the eval estimator's wi and wo (the albedo estimator uses wi only).
struct Pair {
    Vec3 wi, wo;
};

// One lit pixel of a sphere: its place, the light's row, its local directions and cos theta of the light.
struct Pixel {
    int px, py, light;
    Pair local;  // wi the viewer, wo the light (traced so: reciprocity, see sphere_pixels)
    double cos_light;
};

// The lit pixels of a sphere of P pixels across, seen orthographically along +z, the light in the xz-plane at
// light_degrees[light] from the viewer. Pixel (i, j) (j down) has its center at x = (2i + 1 - P)/P,
// y = (P - 1 - 2j)/P, exact multiples of 1/P, so rows j and P-1-j have y of opposite sign, bit for bit. At each pixel
// the sphere's normal n is the macrosurface normal; the local directions are built from n.v, n.l and the azimuth
// between their projections on the tangent plane, all even in y: mirror pixels get the same local geometry to the
// last bit.
//
// The eval estimator gives f(wi, wo) cos theta_o. Tracing the viewer as wi and the light as wo gives
// f(view, light) cos theta_light = f(light, view) cos theta_light (reciprocity), the radiance towards the viewer
// from a unit directional light.
std::vector<Pixel> sphere_pixels(int P, int light);

// A sphere group (one alpha): every light's lit pixels, and the traced ones (the upper half, y >= 0, and the middle
// row: the lower half mirrors them).
struct SphereGroup {
    std::vector<Pixel> pixels;
    std::vector<std::size_t> source;  // per pixel: its index in `traced`
    std::vector<Pair> traced;
};
SphereGroup sphere_group(int P);

// Burley 2012, "Physically-Based Shading at Disney", sec. 2 and fig. "BRDF Explorer slices": the BRDF over
// (theta_h, theta_d) at phi_d = 90 degrees (Rusinkiewicz 1998's half/difference angles, phi_h = 0):
//     wi = (cos td sin th, sin td, cos td cos th),  wo = (cos td sin th, -sin td, cos td cos th),
// both at cos theta = cos td cos th > 0 for cell centers in (0, 90). Cell (i, j): theta_h = (i + 1/2) 90/n across,
// theta_d = (j + 1/2) 90/n down; point k = j n + i.
std::vector<Pair> slice_points(int n);

}  // namespace smithlab::fit
