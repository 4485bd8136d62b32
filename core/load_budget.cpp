#include "core/load_budget.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "core/error.h"

namespace tyndall {

namespace {
[[noreturn]] void refuse(uint64_t bytes, uint64_t limit, uint64_t used, const std::string& what) {
    std::string taken = used > 0 ? ", " + describeBytes(used) + " of it taken by the scene so far" : "";
    throw Error(what + ": needs " + describeBytes(bytes) + ", more than the loading memory budget allows (" +
                std::to_string(limit >> 20) + " MiB" + taken +
                "); raise --load-memory (MiB) if the file is trusted and the machine has the memory");
}
}  // namespace

void LoadBudget::reserve(uint64_t bytes, const std::string& what) {
    uint64_t used = m_used.load();
    do {
        if (bytes > m_limit || used > m_limit - bytes) refuse(bytes, m_limit, used, what);
    } while (!m_used.compare_exchange_weak(used, used + bytes));
}

void LoadBudget::check(uint64_t bytes, const std::string& what) const {
    const uint64_t used = m_used.load();
    if (bytes > m_limit || used > m_limit - bytes) refuse(bytes, m_limit, used, what);
}

uint64_t defaultLoadMemoryBytes() {
    uint64_t bytes = LoadBudget::kDefaultMiB << 20;
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    if (pages > 0 && pageSize > 0) bytes = std::min(bytes, uint64_t(pages) * uint64_t(pageSize) / 4 * 3);
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
        bytes = std::min(bytes, uint64_t(limit.rlim_cur) / 4 * 3);
    return bytes;
}

std::string describeBytes(uint64_t bytes) {
    char text[64];
    const double mib = double(bytes) / double(1 << 20);
    if (mib < 10)
        std::snprintf(text, sizeof text, "%.1f MiB", mib);
    else if (mib < 1e6)
        std::snprintf(text, sizeof text, "%.0f MiB", mib);
    else
        std::snprintf(text, sizeof text, "%.3g TiB", mib / double(1 << 20));
    return text;
}

}  // namespace tyndall
