// smithlab._ndf: NDFs, their Smith functions and samplers (ndfs.cpp). Imported by the package smithlab.
#include "bindings.hpp"

namespace smithlab::python {
void bind_ndfs(py::module_& m);
}

PYBIND11_MODULE(_ndf, m) {
    m.doc() = "smithlab's NDFs, Smith functions and samplers (import smithlab)";
    smithlab::python::translate_errors();
    smithlab::python::bind_ndfs(m);
}
