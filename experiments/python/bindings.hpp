// What the Python module's two extensions share: bad input as ValueError, a seed argument, and the one way an
// elementwise function of NumPy arrays runs (broadcast, float64, the GIL released while C++ loops).
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "evaluation/seed.hpp"
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

// A seed as the command line reads its --seed (an integer in [0, 2^64)), from a Python int or its text.
inline std::uint64_t seed_of(const py::object& seed) {
    return evaluation::parse_seed(py::str(seed).cast<std::string>(), "seed");
}

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// An array's shape as NumPy's messages write it: (100,), (10,10), () for a scalar.
inline std::string shape_text(const Array& a) {
    std::string s = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) {
        if (d > 0) s += ',';
        s += std::to_string(a.shape(d));
    }
    s += a.ndim() == 1 ? ",)" : ")";
    return s;
}

// N inputs broadcast against each other (NumPy's rules: shapes aligned on the right, each dimension equal or 1), each
// read as float64 (anything NumPy reads as numbers), and an output of the broadcast shape: result() is that array, or
// a Python float where every input is a scalar. An input of the output's shape is read in place, one of a single
// value as that value; another is spread to the output's shape once, in C++ (no large temporary for the common case:
// arrays against scalars).
template <std::size_t N>
class Broadcast {
public:
    explicit Broadcast(const std::array<py::object, N>& inputs) {
        std::array<Array, N> a;
        std::vector<py::ssize_t> shape;
        for (std::size_t k = 0; k < N; ++k) {
            a[k] = Array(inputs[k]);  // NumPy's own error where it reads no numbers ("could not convert ...")
            scalar_ = scalar_ && a[k].ndim() == 0;
            shape.resize(std::max<std::size_t>(shape.size(), static_cast<std::size_t>(a[k].ndim())), 1);
        }
        for (std::size_t k = 0; k < N; ++k) {  // the broadcast shape, or NumPy's message
            const std::size_t skip = shape.size() - static_cast<std::size_t>(a[k].ndim());
            for (py::ssize_t d = 0; d < a[k].ndim(); ++d) {
                py::ssize_t& s = shape[skip + static_cast<std::size_t>(d)];
                if (s == 1) s = a[k].shape(d);
                else if (a[k].shape(d) != 1 && a[k].shape(d) != s) throw input_error(mismatch(a));
            }
        }
        out_ = Array(shape);
        for (std::size_t k = 0; k < N; ++k) {
            step_[k] = 1;
            if (a[k].size() == 1) step_[k] = 0, in_[k] = a[k].data();
            else if (static_cast<std::size_t>(a[k].ndim()) == shape.size() &&
                     std::equal(shape.begin(), shape.end(), a[k].shape()))
                in_[k] = a[k].data();
            else spread_[k] = spread(a[k], shape), in_[k] = spread_[k].data();
        }
        keep_ = std::move(a);
    }
    std::size_t size() const { return static_cast<std::size_t>(out_.size()); }
    std::vector<py::ssize_t> shape() const { return {out_.shape(), out_.shape() + out_.ndim()}; }
    bool scalar() const { return scalar_; }
    // input k's value at output index i
    double at(std::size_t k, std::size_t i) const { return in_[k][i * step_[k]]; }
    // input k's values at output indices [first, first + count): in place, or written into `buffer` (count values)
    const double* part(std::size_t k, std::size_t first, std::size_t count, double* buffer) const {
        if (step_[k] == 1) return in_[k] + first;
        std::fill(buffer, buffer + count, in_[k][0]);
        return buffer;
    }
    double* output() { return out_.mutable_data(); }
    py::object result() const {
        if (scalar_) return py::float_(out_.data()[0]);
        return out_;
    }

private:
    // a's values at every index of `shape` (a's dimensions aligned on the right; those of size 1 repeated).
    static std::vector<double> spread(const Array& a, const std::vector<py::ssize_t>& shape) {
        std::size_t n = 1;
        for (const py::ssize_t s : shape) n *= static_cast<std::size_t>(s);
        std::vector<double> out(n);
        if (n == 0 || shape.empty()) {
            if (n == 1) out[0] = a.data()[0];
            return out;
        }
        const std::size_t dims = shape.size(), skip = dims - static_cast<std::size_t>(a.ndim());
        std::vector<py::ssize_t> stride(dims, 0);  // a's stride in values along each output axis (0: repeated)
        for (py::ssize_t d = a.ndim() - 1, step = 1; d >= 0; step *= a.shape(d), --d)
            if (a.shape(d) != 1) stride[skip + static_cast<std::size_t>(d)] = step;
        double* y = out.data();
        fill(a.data(), stride.data(), shape.data(), dims, y);
        return out;
    }
    // Writes x over `shape` (row-major) at y, advancing y: the last axis as a plain loop.
    static void fill(const double* x, const py::ssize_t* stride, const py::ssize_t* shape, std::size_t dims,
                     double*& y) {
        if (dims == 1) {
            for (py::ssize_t i = 0; i < shape[0]; ++i) *y++ = x[i * stride[0]];
            return;
        }
        for (py::ssize_t i = 0; i < shape[0]; ++i) fill(x + i * stride[0], stride + 1, shape + 1, dims - 1, y);
    }
    // NumPy's words: "operands could not be broadcast together with shapes (2,) (3,4)"
    static std::string mismatch(const std::array<Array, N>& a) {
        std::string m = "operands could not be broadcast together with shapes";
        for (const Array& x : a) {
            m += ' ';
            m += shape_text(x);
        }
        return m;
    }

    std::array<Array, N> keep_;
    std::array<std::vector<double>, N> spread_;
    std::array<const double*, N> in_{};
    std::array<std::size_t, N> step_{};  // 1: one value per output index; 0: one value for all
    Array out_;
    bool scalar_ = true;
};

// Ctrl-C during a long call. Python runs its SIGINT handler (KeyboardInterrupt) only when C++ hands control back,
// so a loop that runs without the GIL calls the poll between its pieces (a block of walks, an element): on the
// thread that made it, at most every 0.1 s, it takes the GIL and asks Python for pending signals, and a handler's
// exception (KeyboardInterrupt) is thrown as pybind11's error_already_set, which ends the loop and reaches Python
// as itself. Other threads' calls do nothing: the loop's own machinery stops them (util::reduce_blocks).
class SignalPoll {
public:
    void operator()() const {
        if (std::this_thread::get_id() != owner_) return;
        const auto now = std::chrono::steady_clock::now();
        if (now - last_ < std::chrono::milliseconds(100)) return;
        last_ = now;
        const py::gil_scoped_acquire hold;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }

private:
    std::thread::id owner_ = std::this_thread::get_id();
    mutable std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// f(x0[i], x1[i], ...) over the broadcast inputs (Broadcast). The loop runs in C++ with the GIL released, so f must
// not touch Python; a pending Ctrl-C is honoured between elements (SignalPoll). An exception from f (input_error
// naming the item) propagates after the GIL is taken back.
template <std::size_t N, class F>
py::object elementwise(const F& f, const std::array<py::object, N>& inputs) {
    Broadcast<N> b(inputs);
    double* y = b.output();
    {
        const SignalPoll poll;
        py::gil_scoped_release free;
        for (std::size_t i = 0; i < b.size(); ++i) {
            if (i % 64 == 63) poll();
            y[i] = [&]<std::size_t... K>(std::index_sequence<K...>) { return f(b.at(K, i)...); }
            (std::make_index_sequence<N>{});
        }
    }
    return b.result();
}

}  // namespace smithlab::python
