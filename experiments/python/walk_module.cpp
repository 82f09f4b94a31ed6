// smithlab._walk: the microsurface walk and the fitter's pieces (walk.cpp, fit.cpp). Imported by the package
// smithlab, after smithlab._ndf (whose Ndf objects its functions take).
#include "bindings.hpp"

namespace smithlab::python {
void bind_walk(py::module_& m);
void bind_fit(py::module_& m);
}  // namespace smithlab::python

PYBIND11_MODULE(_walk, m) {
    m.doc() = "smithlab's microsurface walk and diffuse fitter (import smithlab)";
    smithlab::python::translate_errors();
    smithlab::python::bind_walk(m);
    smithlab::python::bind_fit(m);
}
