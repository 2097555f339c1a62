#pragma once
#include <stdexcept>

namespace swell::runtime {

/// An expected failure at the runtime's boundary (STYLE.md #9): no EGL, no usable GL device,
/// a context or shader the driver refuses. Caught in main, printed as one line.
/// Bad parameters throw std::invalid_argument naming the key; broken invariants (bugs)
/// throw std::logic_error.
class RuntimeError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

} // namespace swell::runtime
