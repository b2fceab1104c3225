#pragma once
// Hands a C++ buffer to NumPy without copying: the std::vector moves into a
// capsule that the array keeps alive, and the array views its data.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <utility>
#include <vector>

namespace abbe::python {

namespace py = pybind11;

// A 1-D array of `values` (no copy).
template <typename T>
py::array_t<T> owned_array(std::vector<T>&& values) {
  auto* owner = new std::vector<T>(std::move(values));
  py::capsule free_owner(owner, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>({static_cast<py::ssize_t>(owner->size())}, {sizeof(T)}, owner->data(),
                        free_owner);
}

// An (n, cols) C-ordered array of `values` (size n·cols, row after row; no copy).
template <typename T>
py::array_t<T> owned_matrix(std::vector<T>&& values, std::size_t cols) {
  auto* owner = new std::vector<T>(std::move(values));
  py::capsule free_owner(owner, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  const auto rows = static_cast<py::ssize_t>(owner->size() / cols);
  return py::array_t<T>(
      {rows, static_cast<py::ssize_t>(cols)},
      {static_cast<py::ssize_t>(cols * sizeof(T)), static_cast<py::ssize_t>(sizeof(T))},
      owner->data(), free_owner);
}

}  // namespace abbe::python
