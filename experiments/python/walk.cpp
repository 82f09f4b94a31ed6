#include "bindings.hpp"

namespace smithlab::python {
void bind_walk(py::module_&) {}
}  // namespace smithlab::python
