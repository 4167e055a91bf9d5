#include "terrasynth/guard.h"

#include <new>
#include <stdexcept>

namespace terrasynth {

std::string describeCurrentException() {
    if (!std::current_exception()) return "no exception";
    try {
        throw;
    } catch (const std::bad_alloc&) {
        return "out of memory (std::bad_alloc)";
    } catch (const std::length_error& e) {
        return std::string("a size beyond what fits in memory (std::length_error: ") + e.what() + ")";
    } catch (const std::exception& e) {
        return e.what();
    } catch (...) {
        return "unknown exception";
    }
}

}  // namespace terrasynth
