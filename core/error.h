#pragma once
// Library code throws tyndall::Error; only app/ decides to print and exit. TYNDALL_CHECK is
// always on and names the failed condition with file and line; TYNDALL_ASSERT is debug-only.
#include <cassert>
#include <sstream>
#include <stdexcept>
#include <string>

namespace tyndall {

/// A user-facing failure: the message is one line that names the file/option/place and what
/// was expected, ready to print as "tyndall: <message>".
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

namespace detail {
[[noreturn]] inline void checkFailed(const char* cond, const char* file, int line, const std::string& msg) {
    std::ostringstream s;
    s << msg << " (internal check '" << cond << "' failed at " << file << ":" << line << ")";
    throw Error(s.str());
}
}  // namespace detail

}  // namespace tyndall

#define TYNDALL_CHECK(cond, msg)                                                     \
    do {                                                                             \
        if (!(cond)) ::tyndall::detail::checkFailed(#cond, __FILE__, __LINE__, msg); \
    } while (0)
#define TYNDALL_ASSERT(cond) assert(cond)
