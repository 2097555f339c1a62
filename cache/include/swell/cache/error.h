#pragma once
#include <stdexcept>
#include <string>

namespace swell::cache {

/// An expected failure at the cache boundary: a missing, unreadable, damaged or
/// unsupported file, or an I/O error while writing. The message names the file,
/// the frame (if any) and what is wrong.
class CacheError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

} // namespace swell::cache
