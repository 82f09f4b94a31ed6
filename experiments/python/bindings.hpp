// What the Python module's two extensions share: bad input as ValueError, and the one way an elementwise function of
// NumPy arrays runs (broadcast, float64, the GIL released while C++ loops).
#pragma once

#include <array>
#include <cstddef>
#include <exception>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "smithlab/errors.hpp"

namespace smithlab::python {

namespace py = pybind11;

// input_error (an out-of-domain parameter, an unknown NDF, a malformed spec) raises ValueError with its message,
// which names the item: "gtr: alpha must be in (0, 1], got -1".
inline void translate_errors() {
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const input_error& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        }
    });
}

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// N inputs broadcast against each other (NumPy's rules: np.broadcast_arrays), each as contiguous float64 (anything
// NumPy reads as numbers), and an output of their shape: result() is that array, or a Python float where every input
// is a scalar.
template <std::size_t N>
class Broadcast {
public:
    explicit Broadcast(const std::array<py::object, N>& inputs) {
        py::tuple arrays(N);
        for (std::size_t k = 0; k < N; ++k) {
            Array a = Array::ensure(inputs[k]);
            if (!a) throw py::error_already_set();
            scalar_ = scalar_ && a.ndim() == 0;
            arrays[k] = a;
        }
        const py::list views = py::module_::import("numpy").attr("broadcast_arrays")(*arrays);
        for (std::size_t k = 0; k < N; ++k) in_[k] = Array::ensure(views[k]);
        out_ = Array(std::vector<py::ssize_t>(in_[0].shape(), in_[0].shape() + in_[0].ndim()));
    }
    std::size_t size() const { return static_cast<std::size_t>(out_.size()); }
    std::span<const double> input(std::size_t k) const { return {in_[k].data(), size()}; }
    std::span<double> output() { return {out_.mutable_data(), size()}; }
    py::object result() const {
        if (scalar_) return py::float_(out_.data()[0]);
        return out_;
    }

private:
    std::array<Array, N> in_;
    Array out_;
    bool scalar_ = true;
};

// f(x0[i], x1[i], ...) over the broadcast inputs (Broadcast). The loop runs in C++ with the GIL released, so f must
// not touch Python. An exception from f (input_error naming the item) propagates after the GIL is taken back.
template <std::size_t N, class F>
py::object elementwise(const F& f, const std::array<py::object, N>& inputs) {
    Broadcast<N> b(inputs);
    std::array<std::span<const double>, N> x;
    for (std::size_t k = 0; k < N; ++k) x[k] = b.input(k);
    const std::span<double> y = b.output();
    {
        py::gil_scoped_release free;
        for (std::size_t i = 0; i < y.size(); ++i) y[i] = [&]<std::size_t... K>(std::index_sequence<K...>) {
                return f(x[K][i]...);
            }
        (std::make_index_sequence<N>{});
    }
    return b.result();
}

}  // namespace smithlab::python
