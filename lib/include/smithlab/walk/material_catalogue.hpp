/// @file
/// smithlab/walk/material_catalogue.hpp -- the facet materials parse_material reads (facets.hpp), each by name, its
/// spec with the parameters' defaults, and what it is: one list for the parser's messages and for front ends that
/// list the materials.
#pragma once

#include <array>
#include <string_view>

namespace smithlab::walk {

/// A facet material as parse_material reads it.
struct MaterialInfo {
    /// Its name, its spec with the parameters' defaults ("lambert(albedo=1)"), and what it is.
    /// @{
    std::string_view name, spec, description;
    /// @}
};

/// Every facet material parse_material reads, in the order the messages and front ends list them.
inline constexpr std::array<MaterialInfo, 5> material_catalogue = {{
    {"mirror", "mirror", "every facet a perfect mirror (F = 1)"},
    {"conductor", "conductor(eta=, k=)",
     "mirror facets of a conductor of complex index eta + i k (both required; eta in [1e-6, 1e6], k in [0, 1e6]), "
     "the exact Fresnel reflectance"},
    {"lambert", "lambert(albedo=1)",
     "Lambertian facets, each reflecting albedo / pi about its normal (albedo in [0, 1]; Heitz et al. 2016, sec. "
     "5.3)"},
    {"fresnel-diffuse", "fresnel-diffuse(f0=0.02, albedo=1)",
     "Hammon 2017's facets: Schlick's F (f0 at normal incidence) reflects specularly, the rest leaves diffusely, "
     "tinted by albedo (both in [0, 1])"},
    {"dielectric", "dielectric(eta=1.5)",
     "a smooth dielectric interface on every facet, eta the index below over that above (in [1e-3, 1e3]): "
     "reflection and transmission, light from above or below (Heitz et al. 2016, sec. 6.2)"},
}};

}  // namespace smithlab::walk
