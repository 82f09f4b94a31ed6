// The built-in diffuse models: one line each (each model is its file in fit/diffuse/).
#include "smithlab/fit/diffuse_models.hpp"

namespace smithlab::fit {

void register_core_diffuse_models(DiffuseRegistry& registry) {
    registry.add(lambert_model());
    registry.add(disney_model());
    registry.add(oren_nayar_model());
    registry.add(oren_nayar_sqrt2_model());
    registry.add(oren_nayar_qualitative_model());
    registry.add(fujii_model());
    registry.add(eon_model());
    registry.add(chan_2018_model());
    registry.add(hammon_2017_model());
    registry.add(hammon_2017_linear_model());
    registry.add(smithlab_2026_model());
}

DiffuseRegistry builtin_diffuse_registry() {
    DiffuseRegistry registry;
    register_core_diffuse_models(registry);
    return registry;
}

namespace {

const DiffuseRegistry& builtin_models() {
    static const DiffuseRegistry registry = builtin_diffuse_registry();
    return registry;
}

}  // namespace

const std::vector<DiffuseModel>& diffuse_models() { return builtin_models().list(); }

const DiffuseModel& find_diffuse_model(std::string_view name) { return builtin_models().at(name); }

}  // namespace smithlab::fit
