#include "bindings.hpp"

namespace smithlab::python {
void bind_fit(py::module_&) {}
}  // namespace smithlab::python
